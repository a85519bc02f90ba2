"""A run whose stack never comes up ends with a result that names the missing services, not with silence."""

import threading

from coopdrive.bus import Bus, BusConfig
from coopdrive.launch.ports import free_tcp_port, loopback_endpoint
from coopdrive.launch.processes import ServiceProcesses
from coopdrive.launch.run import RunOptions, build_specs

RESULT_TIMEOUT_S = 60.0


def test_the_simulator_publishes_a_failed_result_naming_the_services_that_never_came_up(tmp_path):
    specs = build_specs(RunOptions(duration_s=5.0), tmp_path)
    sim = next(spec for spec in specs if spec.participant == "world/sim")
    sim.config["startup_timeout_s"] = 1.0
    endpoint = loopback_endpoint(free_tcp_port())
    hub = Bus(BusConfig(listen=[endpoint]))
    results, arrived = [], threading.Event()
    hub.subscribe_key("coopdrive/world/result", lambda key, message: (results.append(message), arrived.set()))
    processes = ServiceProcesses(endpoint, clock="sim", log_dir=tmp_path / "logs")
    try:
        processes.start(sim)  # the stack is never started
        assert arrived.wait(RESULT_TIMEOUT_S), "no result from the simulator"
    finally:
        processes.stop_all()
        hub.close()
    result = results[0]
    assert not result.success
    assert "never started" in result.failure_reason
    assert all(f"ego/{service}" in result.failure_reason for service in ("geolocation", "control", "actuation"))
