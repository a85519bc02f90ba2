"""One run of a sweep, as a Dask task on whichever worker the scheduler picks.

The run is an ordinary lockstep run (so the same seed gives the same metrics as a run made alone), its Zenoh
hub and services on the worker's loopback. Nothing is written where the sweep's client could not read it: the
run's report comes back with its outcome as file contents, so workers on other hosts need no shared folder.
"""

from __future__ import annotations

import functools
import tempfile
from dataclasses import dataclass
from pathlib import Path

from coopdrive.launch.batch import RunOutcome, run_label
from coopdrive.launch.run_spec import RunSpec


@dataclass(frozen=True)
class SweepJob:
    # The run, its fault variant's faults (and any --fault) among its extra faults.
    run: RunSpec
    # The fault variant's name.
    fault: str
    # Write the run's report (metrics, plots, index.html, recording) and send it back.
    report: bool = False

    @property
    def scenario(self) -> str:
        return self.run.scenario

    @property
    def seed(self) -> int:
        return self.run.seed

    @property
    def label(self) -> str:
        return run_label(self.run.scenario, self.fault, self.run.seed)

    def stack_seconds(self) -> float:
        """What the run will cost, to start the costliest runs first: its stack vehicles times its simulated seconds
        (a run's CPU grows with both); 0 for a scenario that does not load, whose run says why itself."""
        return _stack_seconds(self.run.scenario, self.run.stacks, self.run.duration_s)


@functools.cache
def _stack_seconds(scenario: str, stacks: int | None, duration_s: float | None) -> float:
    """SweepJob.stack_seconds, the scenario file read once for all of a sweep's seeds and fault variants."""
    from coopdrive.launch.scenario_source import resolve_scenario
    from coopdrive.services.sim.scenario_config import ScenarioError

    try:
        source = resolve_scenario(scenario)
        stack_count = len(source.stack_vehicles(stacks))
    except ScenarioError:
        return 0.0
    return stack_count * (duration_s if duration_s is not None else source.config.duration_s)


def run_job(job: SweepJob, topic: str) -> tuple[RunOutcome, dict[str, bytes]]:
    """The task: tells the scheduler this attempt started (topic), runs, returns the outcome and the report's
    files by their path in the report folder."""
    from distributed import get_worker

    worker = get_worker()
    # Logged on the scheduler before the run starts: a second attempt of the same run means its worker was lost.
    worker.log_event(topic, {"run": job.label, "worker": worker.address})
    if not job.report:
        return run_one(job, None), {}
    with tempfile.TemporaryDirectory(prefix="coopdrive-sweep-") as folder:
        outcome = run_one(job, Path(folder))
        files = {str(path.relative_to(folder)): path.read_bytes()
                 for path in sorted(Path(folder).rglob("*")) if path.is_file()}
    return outcome, files


def run_one(job: SweepJob, report_dir: Path | None) -> RunOutcome:
    """One run; a run that cannot even start is a failed run, not a failed sweep."""
    from coopdrive.launch.run import RunOptions, run_scenario

    options = RunOptions.of(job.run)
    try:
        if report_dir is None:
            result = run_scenario(options)
        else:
            from coopdrive.judging.commands import run_with_report

            result = run_with_report(options, report_dir)
    except Exception as error:
        return RunOutcome(job.scenario, job.seed, False, f"{type(error).__name__}: {error}", fault=job.fault)
    return RunOutcome(job.scenario, job.seed, result.success, result.failure_reason, result.wall_time_s,
                      dict(result.metrics), fault=job.fault)
