"""Where a sweep's runs go: a Dask cluster, each (scenario, fault variant, seed) one task, results as they finish.

Without --cluster the sweep starts a local cluster of --workers processes; with --cluster it joins a running
`dask scheduler` whose workers may be on other hosts. A worker runs one run at a time (one thread): a run is a
handful of processes of its own. A worker that dies takes its run with it; the scheduler gives the run to another
worker, and after ALLOWED_FAILURES such deaths gives up on it (KilledWorker), which makes a failed run.

Each attempt logs an event on the scheduler when it starts (sweep_task.run_job), so a run that started twice was
retried, and the workers of all its starts but the last were lost under it. The events live on the scheduler,
so this holds for workers on any host.
"""

from __future__ import annotations

import logging
import time
import uuid
from contextlib import contextmanager
from typing import Callable, Iterator

from coopdrive.launch.batch import RunOutcome, SweepEnd
from coopdrive.launch.sweep_order import start_order
from coopdrive.launch.sweep_task import SweepJob, run_job

# How many times a run's worker may die under it before the run counts as failed (Dask's default, said here).
ALLOWED_FAILURES = 3
CONNECT_TIMEOUT_S = 10
# A worker is given its next run when it finishes one, never one ahead (Dask's default, 1.1, hands a one-thread
# worker a second task to hold): a run held behind a long one waits there while another worker goes idle, and the
# sweep's order (sweep_order.py) holds only per worker. Seen in CI: string's seed 2 held behind merge's, cut by the
# time limit, while the other worker ran every shorter run.
WORKER_SATURATION = 1.0


class SweepError(RuntimeError):
    """A sweep that cannot start (no scheduler at --cluster); one line."""


@contextmanager
def sweep_client(cluster: str | None, workers: int) -> Iterator:
    """A Dask client: of the scheduler at `cluster`, or of a local cluster of `workers` processes it closes."""
    import dask
    from distributed import Client, LocalCluster

    if cluster is not None:
        try:
            client = Client(cluster, timeout=CONNECT_TIMEOUT_S, set_as_default=False)
        except (OSError, ValueError, TimeoutError) as error:
            raise SweepError(f"--cluster {cluster}: no Dask scheduler answered ({' '.join(str(error).split())})") \
                from None
        with client:
            yield client
        return
    # The scheduler reads allowed-failures and worker-saturation when it starts; a remote scheduler has its own
    # settings. Workers that are not daemonic processes may fork a run's services from their preloaded server
    # (forked_process.py), which they keep from run to run; a daemonic one starts each service as a new interpreter.
    settings = {"distributed.scheduler.allowed-failures": ALLOWED_FAILURES, "distributed.worker.daemon": False,
                "distributed.scheduler.worker-saturation": WORKER_SATURATION}
    with dask.config.set(settings), _quiet_distributed():
        # No dashboard (bokeh is not installed); the scheduler's HTTP routes on a free loopback port, not on 8787.
        local = LocalCluster(n_workers=max(1, workers), threads_per_worker=1, processes=True,
                             dashboard_address="127.0.0.1:0", scheduler_kwargs={"dashboard": False},
                             silence_logs=logging.ERROR)
        with local, Client(local, set_as_default=False) as client:
            yield client


@contextmanager
def _quiet_distributed() -> Iterator[None]:
    """The local cluster's scheduler and nannies log to this process's console at INFO, through the live table;
    the sweep tells what matters itself (a lost worker as a retried run). The level is set before the cluster
    starts since the cluster puts back, as it closes, the level it found."""
    logger = logging.getLogger("distributed")
    level = logger.level
    logger.setLevel(logging.ERROR)
    try:
        yield
    finally:
        logger.setLevel(level)


def stream_runs(client, jobs: list[SweepJob], on_outcome: Callable[[RunOutcome, dict[str, bytes]], None],
                time_limit_s: float | None = None) -> tuple[list[SweepJob], SweepEnd]:
    """Submits every job, in the order sweep_order.start_order gives, and calls on_outcome(outcome, report files) as
    each run ends, in the order they end. Returns the jobs left unfinished, which are cancelled, when interrupted
    (Ctrl-C) or time_limit_s after the jobs were submitted, and how the sweep ended."""
    from distributed import as_completed

    topic = f"coopdrive-sweep-{uuid.uuid4().hex}"
    ordered = start_order(jobs, time_limited=time_limit_s is not None)
    futures = {client.submit(run_job, job, topic, key=f"coopdrive-run-{job.label}-{topic[-8:]}",
                             priority=len(ordered) - rank): job
               for rank, job in enumerate(ordered)}
    end = SweepEnd.COMPLETE
    submitted_s = time.monotonic()
    try:
        for future in as_completed(list(futures), loop=client.loop, timeout=time_limit_s):
            job = futures.pop(future)
            outcome, files = finished_run(future, job, run_starts(client, topic).get(job.label, []))
            future.release()
            on_outcome(outcome, files)
    except KeyboardInterrupt:
        end = SweepEnd.INTERRUPTED
    except TimeoutError:
        if time_limit_s is None or time.monotonic() - submitted_s < time_limit_s:
            raise  # not the limit's: the scheduler did not answer
        end = SweepEnd.TIME_LIMIT
    if futures:
        client.cancel(list(futures))
    return list(futures.values()), end


def run_starts(client, topic: str) -> dict[str, list[str]]:
    """Run label -> the workers its attempts started on, in order."""
    starts: dict[str, list[str]] = {}
    for _time, event in client.get_events(topic):
        starts.setdefault(event["run"], []).append(event["worker"])
    return starts


def finished_run(future, job: SweepJob, starts: list[str]) -> tuple[RunOutcome, dict[str, bytes]]:
    """The run's outcome and report files from its ended future, with the workers that died under it (`starts`:
    the workers its attempts started on)."""
    from distributed import KilledWorker

    try:
        outcome, files = future.result()
        lost = starts[:-1]  # the last start is the one that ended
    except KilledWorker:
        outcome, files = _not_run(job, "each worker it was given died running it (KilledWorker)"), {}
        lost = list(starts)
    except Exception as error:  # the task itself failed, e.g. on a worker without coopdrive installed
        outcome, files = _not_run(job, f"{type(error).__name__}: {' '.join(str(error).split())}"), {}
        lost = starts[:-1]
    outcome.lost_workers, outcome.retried = lost, bool(lost)
    return outcome, files


def _not_run(job: SweepJob, reason: str) -> RunOutcome:
    return RunOutcome(job.scenario, job.seed, False, f"not run: {reason}", fault=job.fault)
