"""Sweeps on a Dask cluster (a LocalCluster here, joined by its address as a remote one would be): each run gives
what the same run gives alone, and a worker killed mid-run loses no run: it is run again and said to be."""

import os
import signal
import threading
import time

from types import SimpleNamespace

import psutil
import pytest
from distributed import Client, KilledWorker
from rich.console import Console

from coopdrive.launch.batch import BatchOptions
from coopdrive.launch.run import RunOptions, run_scenario
from coopdrive.launch.batch import RunOutcome
from coopdrive.launch.sweep_cluster import WORKER_SATURATION, SweepError, finished_run, sweep_client
from coopdrive.launch.process_layout import ProcessLayout
from coopdrive.launch.run_spec import RunSpec
from coopdrive.launch.sweep import run_batch
from coopdrive.launch.sweep_task import SweepJob

pytestmark = pytest.mark.whole_run

SEEDS = [1, 2, 3, 4]
DURATION_S = 3.0


@pytest.fixture(scope="module")
def cluster():
    """A local cluster of two workers, as a sweep starts it; the sweeps join it by its address."""
    with sweep_client(None, 2) as client:
        yield client.scheduler.address, client


@pytest.fixture(scope="module")
def alone():
    """Seed -> the metrics of the follow run made alone, in this process."""
    return {seed: dict(run_scenario(RunOptions(scenario="follow", seed=seed, duration_s=DURATION_S)).metrics)
            for seed in SEEDS}


def sweep(address: str, console: Console, seeds: list[int]):
    return run_batch(BatchOptions(scenarios=["follow"], seeds=seeds, run=RunSpec(processes=ProcessLayout.ONE, duration_s=DURATION_S),
                                  cluster=address),
                     console)


def test_every_run_of_a_four_seed_sweep_on_two_workers_equals_the_same_run_made_alone(cluster, alone):
    address, _client = cluster
    console = Console(record=True, width=200)
    summary = sweep(address, console, SEEDS)
    by_seed = {outcome.seed: outcome for outcome in summary.outcomes}
    assert sorted(by_seed) == SEEDS
    for seed in SEEDS:
        assert by_seed[seed].success and not by_seed[seed].retried
        assert by_seed[seed].metrics == alone[seed]
    printed = console.export_text()
    assert "coopdrive batch" in printed and "retried" in printed and "100%" in printed


def running(process: psutil.Process) -> bool:
    try:
        return process.status() != psutil.STATUS_ZOMBIE
    except psutil.NoSuchProcess:
        return False


def kill_a_worker_mid_run(client: Client, killed: dict) -> None:
    """Waits for a worker whose run's services are up (the same task, with child processes, at two looks half a
    second apart), then SIGKILLs it."""
    pids = client.run(os.getpid)
    seen: dict[str, str] = {}
    deadline = time.monotonic() + 120
    while time.monotonic() < deadline:
        executing = {worker: next(iter(keys)) for worker, keys in client.call_stack().items() if keys}
        for worker, key in executing.items():
            services = psutil.Process(pids[worker]).children(recursive=True)
            if services and seen.get(worker) == key:
                killed.update(worker=worker, key=key, services=services)
                os.kill(pids[worker], signal.SIGKILL)
                return
        seen = {worker: key for worker, key in executing.items() if psutil.Process(pids[worker]).children()}
        time.sleep(0.5)


def test_a_worker_killed_mid_run_loses_no_run_and_its_run_is_run_again_and_marked_retried(cluster, alone):
    address, client = cluster
    killed: dict = {}
    killer = threading.Thread(target=kill_a_worker_mid_run, args=(client, killed), daemon=True)
    killer.start()
    console = Console(record=True, width=200)
    summary = sweep(address, console, SEEDS[:2])  # a run on each worker: one of them is killed under its run
    killer.join()
    assert killed, "no worker was seen running a task"
    by_seed = {outcome.seed: outcome for outcome in summary.outcomes}
    assert sorted(by_seed) == SEEDS[:2]
    assert all(outcome.success and outcome.metrics == alone[outcome.seed] for outcome in summary.outcomes)
    [retried] = [outcome for outcome in summary.outcomes if outcome.retried]
    assert f"-{retried.label}-" in killed["key"] and retried.lost_workers == [killed["worker"]]
    assert f"retried {retried.label} after its worker died: {killed['worker']}" in console.export_text()
    # The killed run's simulator and stack, orphaned, end by themselves.
    assert killed["services"]
    deadline = time.monotonic() + 15
    while any(running(process) for process in killed["services"]) and time.monotonic() < deadline:
        time.sleep(0.2)
    assert not any(running(process) for process in killed["services"])


def started_runs(cluster, time_limit_s: float | None = None) -> list[str]:
    """Sweeps follow and platoon40 on seeds 1 and 2 (1 s each) and gives the labels of its runs as they started."""
    address, client = cluster
    earlier_sweeps = set(client.get_events())
    summary = run_batch(BatchOptions(scenarios=["follow", "platoon40"], seeds=[1, 2],
                                     run=RunSpec(processes=ProcessLayout.ONE, duration_s=1.0),
                                     cluster=address, time_limit_s=time_limit_s), Console(record=True, width=200))
    assert len(summary.outcomes) == 4
    [topic] = [topic for topic in client.get_events() if topic.startswith("coopdrive-sweep-")
               and topic not in earlier_sweeps]
    return [event["run"] for _time, event in sorted(client.get_events(topic), key=lambda timed: timed[0])]


def test_a_sweep_starts_its_costliest_runs_first_wherever_the_scenarios_list_them(cluster):
    """platoon40 runs three stacks where follow runs one: listed last, its runs still take both workers first."""
    assert [run.split("/")[0] for run in started_runs(cluster)] == ["platoon40"] * 2 + ["follow"] * 2


def test_a_sweep_with_a_time_limit_starts_every_scenario_on_the_first_seed_before_any_on_the_second(cluster):
    assert [run.split("/")[-1] for run in started_runs(cluster, time_limit_s=300.0)] == ["seed-1"] * 2 + ["seed-2"] * 2


def test_a_cluster_address_where_no_scheduler_answers_is_one_line(monkeypatch):
    monkeypatch.setattr("coopdrive.launch.sweep_cluster.CONNECT_TIMEOUT_S", 1)
    with pytest.raises(SweepError, match=r"^--cluster tcp://127.0.0.1:9: no Dask scheduler answered \(.*\)$"):
        with sweep_client("tcp://127.0.0.1:9", 2):
            pass


class Ended:
    """A future that has ended with this value or error."""

    def __init__(self, value=None, error=None):
        self.value, self.error = value, error

    def result(self):
        if self.error is not None:
            raise self.error
        return self.value


def test_a_run_given_up_on_after_its_workers_died_is_a_failed_run_that_lost_each_of_them():
    job = SweepJob(RunSpec(scenario="follow", seed=3), "none")
    gave_up = KilledWorker("coopdrive-run-follow/none/seed-3", SimpleNamespace(address="tcp://b:1"), 1)
    outcome, files = finished_run(Ended(error=gave_up), job, ["tcp://a:1", "tcp://b:1"])
    assert (outcome.seed, outcome.success, files) == (3, False, {})
    assert outcome.failure_reason == "not run: each worker it was given died running it (KilledWorker)"
    assert outcome.retried and outcome.lost_workers == ["tcp://a:1", "tcp://b:1"]


def test_a_run_that_ended_on_its_second_start_lost_only_the_first_worker():
    ran = RunOutcome("follow", 3, True, "", fault="none")
    outcome, files = finished_run(Ended((ran, {"index.html": b""})), SweepJob(RunSpec(scenario="follow", seed=3), "none"),
                                  ["tcp://a:1", "tcp://b:1"])
    assert outcome.success and files == {"index.html": b""}
    assert outcome.retried and outcome.lost_workers == ["tcp://a:1"]


def test_a_task_that_raised_is_a_failed_run_in_one_line_and_not_a_retried_one():
    error = ModuleNotFoundError("No module named 'coopdrive'\n(on the worker)")
    outcome, _ = finished_run(Ended(error=error), SweepJob(RunSpec(scenario="follow", seed=1), "none"), ["tcp://a:1"])
    assert outcome.failure_reason == "not run: ModuleNotFoundError: No module named 'coopdrive' (on the worker)"
    assert not outcome.retried


def test_the_local_cluster_gives_a_worker_its_next_run_only_when_it_has_finished_one(cluster):
    """No run is held on a busy worker, so the sweep's order holds across the workers, not per worker."""
    _address, client = cluster
    assert client.run_on_scheduler(lambda dask_scheduler: dask_scheduler.WORKER_SATURATION) == WORKER_SATURATION == 1.0
