"""Every process layout of a run gives the metrics of one process per service (the vehicle's layout), services
forked from the preloaded server give the metrics of services started as new interpreters, and a run in one
process stops as cleanly as one in many, its simulator last, and records a run each service's replay reproduces."""

import subprocess
import sys

import pytest

from coopdrive.launch.process_layout import ProcessLayout
from coopdrive.launch.processes import NEW_INTERPRETERS_VARIABLE, ServiceProcesses
from coopdrive.launch.run import ONE_PROCESS_NAME, RunOptions, run_scenario
from coopdrive.recording.replay import replay_service
from coopdrive.runtime.registry import VEHICLE_STACK

pytestmark = pytest.mark.whole_run

SCENARIO = "platoon40"
STACKS = 2
DURATION_S = 5.0
SWEEP_WAIT_S = 240


@pytest.fixture(scope="module")
def one_process_recording(tmp_path_factory):
    recording = tmp_path_factory.mktemp("one") / "follow.mcap"
    result = run_scenario(RunOptions(duration_s=DURATION_S, processes=ProcessLayout.ONE, record=recording))
    assert result.success, result.failure_reason
    return recording


def metrics_with(processes: ProcessLayout) -> dict[str, float]:
    result = run_scenario(RunOptions(scenario=SCENARIO, seed=3, stacks=STACKS, duration_s=DURATION_S,
                                     processes=processes))
    assert result.success, result.failure_reason
    return dict(result.metrics)


@pytest.fixture(scope="module")
def layout_metrics() -> dict[ProcessLayout, dict[str, float]]:
    """Each layout's metrics, run once for the whole file whichever test asks first (services forked from the
    preloaded server, as every run starts them unless told otherwise)."""
    return {layout: metrics_with(layout) for layout in (ProcessLayout.SERVICE, ProcessLayout.VEHICLE)}


def test_two_stacks_each_in_one_process_give_the_metrics_of_one_process_per_service(layout_metrics):
    assert layout_metrics[ProcessLayout.VEHICLE] == layout_metrics[ProcessLayout.SERVICE]


def test_the_simulator_and_two_stacks_in_one_process_give_the_metrics_of_one_process_per_service(layout_metrics):
    assert metrics_with(ProcessLayout.ONE) == layout_metrics[ProcessLayout.SERVICE]


def test_services_forked_from_the_preloaded_server_give_the_metrics_of_new_interpreters(layout_metrics, monkeypatch):
    monkeypatch.setenv(NEW_INTERPRETERS_VARIABLE, "1")
    assert metrics_with(ProcessLayout.VEHICLE) == layout_metrics[ProcessLayout.VEHICLE]


def test_the_one_process_of_a_run_ends_by_itself_on_the_launchers_sigterm(monkeypatch):
    """Its clock's runner takes the signal too, and stops waiting for it (a SIGKILL after the grace: -9)."""
    exit_codes = {}
    stop_all = ServiceProcesses.stop_all

    def stop_and_keep_exit_codes(processes):
        stop_all(processes)
        exit_codes.update({name: process.returncode for name, process in processes.processes.items()})

    monkeypatch.setattr(ServiceProcesses, "stop_all", stop_and_keep_exit_codes)
    result = run_scenario(RunOptions(duration_s=2.0, processes=ProcessLayout.ONE))
    assert result.success and exit_codes == {ONE_PROCESS_NAME: 0}, (result.failure_reason, exit_codes)


@pytest.mark.parametrize("service", VEHICLE_STACK)
def test_replaying_a_service_of_a_run_in_one_process_reproduces_its_recorded_outputs_exactly(one_process_recording,
                                                                                            service, tmp_path):
    result = replay_service(one_process_recording, service, out=tmp_path / f"{service}.mcap")
    assert result.recorded_outputs and result.mismatches() == []


def test_in_one_process_the_simulator_stops_after_the_stacks_so_none_reads_a_closed_gnss_port():
    """The world outlives the vehicles: a stack's last step may still read the GNSS pty the simulator writes. Seen
    in sweeps, where every run ended with each stack's geolocation warning of a failed port."""
    finished = subprocess.run([sys.executable, "-m", "coopdrive.cli", "run", SCENARIO, "--seeds", "1-2", "--workers",
                               "2", "--duration", "3", "--stacks", str(STACKS), "--processes", "one"],
                              capture_output=True, text=True, timeout=SWEEP_WAIT_S)
    assert finished.returncode == 0, finished.stderr[-2000:]
    assert "GNSS port" not in finished.stderr, finished.stderr[-2000:]
