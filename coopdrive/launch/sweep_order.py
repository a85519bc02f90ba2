"""The order a sweep starts its runs in, given to Dask as priorities (sweep_cluster.stream_runs).

Without a time limit what matters is when the last run ends: the costliest runs go first (longest processing time
first), so a sweep's last runs are its short ones and its workers end close together. With a time limit what
matters is what has run when the limit comes: the runs go seed by seed, every scenario and fault variant of a seed
before any of the next, so a sweep cut short has run every scenario on its first seeds rather than its longest
scenarios on every seed; within a seed the cheapest go first, since the shortest first is the order that finishes
the most runs by a deadline (CI's seeds 1-2 in a slow hour: follow and localisation finish where merge and string,
started first, would have held both workers to the limit and finished nothing). On a few workers both orders end
at about the same time; on many, rounds by seed can end up to one long run later.
"""

from __future__ import annotations

from coopdrive.launch.sweep_task import SweepJob


def start_order(jobs: list[SweepJob], time_limited: bool) -> list[SweepJob]:
    """The jobs in the order they should start: by seed when time_limited (seeds in the order the sweep lists them)
    and the cheapest first within a seed (SweepJob.stack_seconds), else the costliest first over the whole sweep;
    ties keep their order."""
    if not time_limited:
        return sorted(jobs, key=lambda job: -job.stack_seconds())
    round_of = {seed: index for index, seed in enumerate(dict.fromkeys(job.seed for job in jobs))}
    return sorted(jobs, key=lambda job: (round_of[job.seed], job.stack_seconds()))
