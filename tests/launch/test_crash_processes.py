"""The launcher's side of service_crash: the crashed service in a process of its own, restarted on demand."""

import time

from coopdrive.launch.processes import ServiceProcesses, ServiceSpec
from coopdrive.launch.run import RunOptions, build_specs, carry_out, crashing_participants, start_processes
from coopdrive.v1 import sim_pb2

CRASH = {"type": "service_crash", "vehicle_id": "p1", "service": "control", "start_s": 4, "end_s": 7}


class StartedProcesses(ServiceProcesses):
    """Notes which processes a run would start, without starting them."""

    def __init__(self):
        super().__init__("tcp/127.0.0.1:1")
        self.started: list[tuple[str, list[str]]] = []

    def start(self, spec):
        self.started.append((spec.participant, [spec.participant]))

    def start_group(self, name, specs):
        self.started.append((name, [spec.participant for spec in specs]))


def test_the_crashed_service_runs_alone_while_the_rest_of_its_vehicle_shares_a_process(tmp_path):
    options = RunOptions(scenario="platoon40", stacks=2, extra_faults=(CRASH,))
    specs = build_specs(options, tmp_path)
    assert crashing_participants(specs) == {"p1/control"}
    processes = StartedProcesses()
    start_processes(processes, specs, options)
    started = dict(processes.started)
    assert started["p1/control"] == ["p1/control"]
    assert "p1/control" not in started["p1/group"] and "p1/actuation" in started["p1/group"]
    assert "p2/control" in started["p2/group"]


def wait_for_exit(process, timeout_s=60.0):
    deadline = time.monotonic() + timeout_s
    while process.poll() is None and time.monotonic() < deadline:
        time.sleep(0.1)
    return process.returncode


def test_a_killed_service_is_started_again_with_the_same_command_and_its_log_goes_on(tmp_path):
    # A group file that does not exist: the process fails at once, which is all a restart needs to show.
    processes = ServiceProcesses("tcp/127.0.0.1:1", log_dir=tmp_path)
    try:
        processes._spawn("v/control", [ServiceSpec("control", "v", {})], ["group", str(tmp_path / "missing.json")])
        first = processes.processes["v/control"]
        assert wait_for_exit(first) != 0
        carry_out(processes, sim_pb2.ServiceFault(participant="v/control", restart=True))
        second = processes.processes["v/control"]
        assert second.pid != first.pid and second.args == first.args
        assert wait_for_exit(second) != 0
        carry_out(processes, sim_pb2.ServiceFault(participant="nobody/control"))  # not ours: nothing happens
        log = (tmp_path / "v-control.log").read_text()
        assert log.count("missing.json") >= 2, log
    finally:
        processes.stop_all()


class _Ended:
    """A process that has ended: what exited() and restart() ask of one."""

    returncode = -9

    def poll(self) -> int:
        return self.returncode

    def wait(self, timeout=None) -> int:
        return self.returncode


class _MergeTold:
    """What the spool merge is told: spools added and spools whose writer is gone."""

    def __init__(self):
        self.added, self.gone = [], []

    def add(self, path):
        self.added.append(path.name)

    def writer_gone(self, path):
        self.gone.append(path.name)


def test_a_restarted_service_s_new_spool_is_not_taken_for_whole_while_its_process_is_still_starting(tmp_path,
                                                                                                 monkeypatch):
    """The launcher's thread asks exited() while restart() is forking the new process: it still sees the old one,
    ended. Its end must close the old spool only: the new one, told whole before its process wrote anything, left
    the restarted service's messages out of the recording (4 runs of 5 under load, test_service_crash_run.py)."""
    import coopdrive.launch.processes as processes_module

    merge = _MergeTold()
    processes = ServiceProcesses("tcp/127.0.0.1:1", spool_dir=tmp_path, spool_merge=merge)

    def started_while_the_launcher_polls(*_arguments):
        processes.exited()  # the launcher's thread, mid-start
        return _Ended()

    monkeypatch.setattr(processes_module, "ForkedProcess", started_while_the_launcher_polls)
    processes.start(ServiceSpec("control", "p1", {}))
    processes.restart("p1/control")
    assert merge.added == ["p1-control-0.spool.mcap", "p1-control-1.spool.mcap"]
    assert "p1-control-1.spool.mcap" not in merge.gone and "p1-control-0.spool.mcap" in merge.gone
