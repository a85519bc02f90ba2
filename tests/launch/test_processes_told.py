"""A run tells whoever asks (RunOptions.on_process_started) of each process it starts, with its name and pid, so a
tool finds the gateway's process through the launcher rather than by scanning /proc for names."""

import os

import pytest

from coopdrive.launch.ports import free_tcp_port
from coopdrive.launch.processes import ServiceProcesses, ServiceSpec
from coopdrive.launch.run import RunOptions, run_scenario

pytestmark = pytest.mark.whole_run

RUN_S = 1.0


def alive(pid: int) -> bool:
    try:
        os.kill(pid, 0)
    except ProcessLookupError:
        return False
    return True


def test_a_run_tells_each_process_it_starts_by_name_with_its_pid_while_it_runs():
    told: list[tuple[str, int, bool]] = []
    result = run_scenario(RunOptions(duration_s=RUN_S, gateway_port=free_tcp_port(),
                                     on_process_started=lambda name, pid: told.append((name, pid, alive(pid)))))
    assert result.success, result.failure_reason
    assert sorted(name for name, _, _ in told) == ["ego/gateway", "ego/group", "world/sim"]
    assert all(running for _, _, running in told) and len({pid for _, pid, _ in told}) == 3


def test_a_process_started_again_after_a_crash_is_told_again_with_its_new_pid():
    told: list[tuple[str, int]] = []
    # A planner on an endpoint where nobody listens: it waits for a clock that never comes.
    processes = ServiceProcesses("tcp/127.0.0.1:1", on_started=lambda name, pid: told.append((name, pid)))
    try:
        processes.start_group("v/group", [ServiceSpec("planner", "v", {})])
        processes.restart("v/planner")
    finally:
        processes.stop_all()
    assert [name for name, _ in told] == ["v/group", "v/group"]
    assert told[0][1] != told[1][1]
