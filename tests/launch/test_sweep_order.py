"""The order a sweep starts its runs in: the costliest first, or seed by seed (the cheapest first within a seed) when
the sweep has a time limit."""

from coopdrive.launch.sweep_order import start_order
from coopdrive.launch.run_spec import RunSpec
from coopdrive.launch.sweep_task import SweepJob

# Stack vehicles times simulated seconds: follow 1 x 60, platoon40 3 x 60, merge 6 x 90.
JOBS = [SweepJob(RunSpec(scenario=scenario, seed=seed), "none") for scenario in ("follow", "merge", "platoon40") for seed in (1, 2)]


def labels(jobs: list[SweepJob]) -> list[str]:
    return [f"{job.scenario}/{job.seed}" for job in jobs]


def test_without_a_time_limit_the_costliest_runs_start_first_whatever_their_seed():
    assert labels(start_order(JOBS, time_limited=False)) == [
        "merge/1", "merge/2", "platoon40/1", "platoon40/2", "follow/1", "follow/2"]


def test_with_a_time_limit_every_scenario_s_first_seed_starts_before_any_second_cheapest_first_within_a_seed():
    assert labels(start_order(JOBS, time_limited=True)) == [
        "follow/1", "platoon40/1", "merge/1", "follow/2", "platoon40/2", "merge/2"]


def test_seeds_go_in_the_order_the_sweep_lists_them():
    jobs = [SweepJob(RunSpec(scenario="follow", seed=seed), "none") for seed in (7, 3)] + [SweepJob(RunSpec(scenario="merge", seed=seed), "none") for seed in (7, 3)]
    assert labels(start_order(jobs, time_limited=True)) == ["follow/7", "merge/7", "follow/3", "merge/3"]
