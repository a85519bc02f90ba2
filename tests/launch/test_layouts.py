"""Every process layout of a run gives the metrics of one process per service (the vehicle's layout), and services
forked from the preloaded server give the metrics of services started as new interpreters."""

from coopdrive.launch.processes import NEW_INTERPRETERS_VARIABLE
from coopdrive.launch.run import RunOptions, run_scenario

SCENARIO = "platoon40"
STACKS = 2
DURATION_S = 8.0


def metrics_with(group_per_vehicle: bool) -> dict[str, float]:
    result = run_scenario(RunOptions(scenario=SCENARIO, seed=3, stacks=STACKS, duration_s=DURATION_S,
                                     group_per_vehicle=group_per_vehicle))
    assert result.success, result.failure_reason
    return dict(result.metrics)


def test_two_stacks_each_in_one_process_give_the_metrics_of_one_process_per_service():
    assert metrics_with(group_per_vehicle=True) == metrics_with(group_per_vehicle=False)


def test_services_forked_from_the_preloaded_server_give_the_metrics_of_new_interpreters(monkeypatch):
    forked = metrics_with(group_per_vehicle=True)
    monkeypatch.setenv(NEW_INTERPRETERS_VARIABLE, "1")
    assert metrics_with(group_per_vehicle=True) == forked
