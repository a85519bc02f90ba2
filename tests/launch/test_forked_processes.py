"""A run's services are forked from a server that imported their modules once; a daemonic process, which may not
fork children, starts them as new interpreters instead; a launching script is not run again in its services (a
test of a forked service's log and restart: test_crash_processes.py)."""

import json
import multiprocessing
import os
import subprocess
import sys
import time

import pytest

from coopdrive.launch.forked_process import ForkedProcess
from coopdrive.launch.processes import NEW_INTERPRETERS_VARIABLE, ServiceProcesses

ANSWER_WAIT_S = 60.0
# Without the fix a script without a guard starts a run in each service, which starts runs... until this ends it.
RUN_WAIT_S = 120.0


def start_a_waiting_group(folder) -> tuple[str, int, int | None]:
    """Starts a stack's planner as a group on an endpoint where nobody listens (it waits for a clock that never
    comes) and stops it; (the kind of process, its parent's pid, its exit code once stopped)."""
    spec = folder / "group.json"
    spec.write_text(json.dumps([{"service": "planner", "vehicle": "v", "config": {}}]))
    processes = ServiceProcesses("tcp/127.0.0.1:1")
    try:
        processes._spawn("v/group", [], ["group", str(spec)])
        process = processes.processes["v/group"]
        with open(f"/proc/{process.pid}/stat") as stat:
            parent_pid = int(stat.read().rsplit(")", 1)[1].split()[1])
    finally:
        processes.stop_all()
    return type(process).__name__, parent_pid, process.poll()


def test_a_service_is_forked_from_the_preloaded_server_and_stops_when_told(tmp_path):
    kind, parent_pid, exit_code = start_a_waiting_group(tmp_path)
    assert kind == ForkedProcess.__name__ and parent_pid != os.getpid() and exit_code is not None


def test_a_forked_service_shows_its_command_in_its_process_title_as_a_new_interpreter_would(tmp_path):
    spec = tmp_path / "group.json"
    spec.write_text(json.dumps([{"service": "planner", "vehicle": "v", "config": {}}]))
    processes = ServiceProcesses("tcp/127.0.0.1:1")
    title = ""
    try:
        processes._spawn("v/group", [], ["group", str(spec)])
        deadline = time.monotonic() + ANSWER_WAIT_S
        while not title.startswith("coopdrive group") and time.monotonic() < deadline:
            with open(f"/proc/{processes.processes['v/group'].pid}/cmdline", "rb") as cmdline:
                title = cmdline.read().replace(b"\0", b" ").decode().strip()
            time.sleep(0.05)
    finally:
        processes.stop_all()
    assert title.startswith(f"coopdrive group {spec} --connect tcp/127.0.0.1:1"), title


def _start_in_a_daemon(folder, answers) -> None:
    answers.put(start_a_waiting_group(folder))


def test_a_daemonic_process_starts_its_services_as_new_interpreters(tmp_path):
    context = multiprocessing.get_context("spawn")
    answers = context.Queue()
    daemon = context.Process(target=_start_in_a_daemon, args=(tmp_path, answers), daemon=True)
    daemon.start()
    kind, parent_pid, exit_code = answers.get(timeout=ANSWER_WAIT_S)
    daemon.join(ANSWER_WAIT_S)
    assert kind == subprocess.Popen.__name__ and parent_pid == daemon.pid and exit_code is not None


def test_the_new_interpreters_variable_starts_services_as_new_interpreters(tmp_path, monkeypatch):
    monkeypatch.setenv(NEW_INTERPRETERS_VARIABLE, "1")
    kind, parent_pid, exit_code = start_a_waiting_group(tmp_path)
    assert kind == subprocess.Popen.__name__ and parent_pid == os.getpid() and exit_code is not None


# A launcher whose fork server is to preload a module that fails as it is imported (as a service with a typo would).
BROKEN_PRELOAD_LAUNCHER = """
import coopdrive.launch.forked_process as forked
from coopdrive.launch.processes import ServiceProcesses
from coopdrive.launch.run_aborted import RunAborted
forked.FRAMEWORK_MODULES = (*forked.FRAMEWORK_MODULES, "broken_service_module")
try:
    ServiceProcesses("tcp/127.0.0.1:1")._spawn("v/group", [], ["group", "unused.json"])
except RunAborted as error:
    print(error)
"""


def test_a_module_that_fails_to_import_in_the_fork_server_aborts_the_run_with_one_line_naming_it(tmp_path):
    (tmp_path / "broken_service_module.py").write_text("name_that_is_not_defined\n")
    environment = {**os.environ, "PYTHONPATH": str(tmp_path)}  # where the server finds the module
    finished = subprocess.run([sys.executable, "-c", BROKEN_PRELOAD_LAUNCHER], capture_output=True, text=True,
                              timeout=ANSWER_WAIT_S, env=environment)
    assert finished.stdout.startswith("the server that forks the services failed"), finished.stdout
    assert "broken_service_module" in finished.stderr and "NameError" in finished.stderr


# A user's script without an `if __name__ == "__main__":` guard: multiprocessing would run it again in each service.
UNGUARDED_SCRIPT = """
import os
print("the script runs in", os.getpid(), flush=True)
from coopdrive.launch.run import RunOptions, run_scenario
print("success:", run_scenario(RunOptions(duration_s=0.5)).success, flush=True)
"""


@pytest.mark.parametrize("from_stdin", [False, True], ids=["a file", "stdin"])
def test_a_run_started_by_a_script_without_a_main_guard_runs_the_script_once(tmp_path, from_stdin):
    script = tmp_path / "unguarded.py"
    script.write_text(UNGUARDED_SCRIPT)
    finished = subprocess.run([sys.executable, "-" if from_stdin else str(script)], capture_output=True, text=True,
                              timeout=RUN_WAIT_S, input=UNGUARDED_SCRIPT if from_stdin else None, cwd=tmp_path)
    assert finished.stdout.count("the script runs in") == 1, finished.stdout + finished.stderr[-2000:]
    assert "success: True" in finished.stdout, finished.stderr[-2000:]


def test_signalling_a_service_that_ended_before_the_fork_server_said_so_does_nothing():
    """The fork server reaps its children and reports their exit a moment later: in between, the pid is gone while
    the exit code is still unknown (a stop of a simulator that gave up at its start timeout once raised here)."""
    ended = subprocess.Popen([sys.executable, "-c", "pass"])
    ended.wait()  # reaped: its pid names no process
    process = ForkedProcess.__new__(ForkedProcess)
    process._process = multiprocessing.Process()  # never started: its exit code is None, as one not yet reported
    process.pid = ended.pid
    process.send_signal(15)
    assert process.poll() is None
