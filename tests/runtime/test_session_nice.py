"""COOPDRIVE_SESSION_NICE: every coopdrive command gives its session the nice value asked for (the kernel shares the
cores between sessions first), so a sweep started beside other work, as CI's is, stays behind it."""

import os
import subprocess
import sys
import time
from pathlib import Path

import pytest

from coopdrive.runtime import priority
from coopdrive.runtime.config import ConfigError
from coopdrive.runtime.priority import SESSION_NICE_VARIABLE, nice_session_as_asked

pytestmark = pytest.mark.whole_run

AUTOGROUPS = Path("/proc/self/autogroup").exists()


@pytest.fixture
def autogroup_file(tmp_path, monkeypatch) -> Path:
    path = tmp_path / "autogroup"
    monkeypatch.setattr(priority, "AUTOGROUP", path)
    return path


def test_without_the_variable_the_session_is_left_as_it_is(autogroup_file, monkeypatch):
    monkeypatch.delenv(SESSION_NICE_VARIABLE, raising=False)
    nice_session_as_asked()
    assert not autogroup_file.exists()


def test_the_variable_s_value_is_written_as_the_session_s_nice_value(autogroup_file, monkeypatch):
    monkeypatch.setenv(SESSION_NICE_VARIABLE, "19")
    nice_session_as_asked()
    assert autogroup_file.read_text() == "19"


def test_a_kernel_without_autogroups_leaves_the_command_running(tmp_path, monkeypatch):
    monkeypatch.setattr(priority, "AUTOGROUP", tmp_path / "no such folder" / "autogroup")
    monkeypatch.setenv(SESSION_NICE_VARIABLE, "19")
    nice_session_as_asked()


@pytest.mark.parametrize("value", ["low", "20", "-21", "1.5"])
def test_a_value_that_is_no_nice_value_is_refused_naming_the_variable(autogroup_file, monkeypatch, value):
    monkeypatch.setenv(SESSION_NICE_VARIABLE, value)
    with pytest.raises(ConfigError, match=f"{SESSION_NICE_VARIABLE}='{value}'"):
        nice_session_as_asked()
    assert not autogroup_file.exists()


def test_the_command_stops_in_one_line_on_a_bad_value():
    completed = subprocess.run([sys.executable, "-m", "coopdrive.cli", "scenarios"], capture_output=True, text=True,
                               timeout=60, env={**os.environ, SESSION_NICE_VARIABLE: "low"})
    assert completed.returncode == 2
    assert completed.stderr == (f"coopdrive: {SESSION_NICE_VARIABLE}='low': a nice value is a whole number from -20 "
                                "to 19\n")


def _descendants(root: int) -> set[int]:
    parents = {}
    for stat in Path("/proc").glob("[0-9]*/stat"):
        try:
            fields = stat.read_text().rsplit(")", 1)[1].split()
        except OSError:
            continue
        parents[int(stat.parent.name)] = int(fields[1])
    found, frontier = set(), {root}
    while frontier:
        frontier = {pid for pid, parent in parents.items() if parent in frontier} - found
        found |= frontier
    return found


# Any value but the default 0 shows each session takes it. Not CI sweep's 19: under the suite's other worker a run at
# 19 gets a sixtieth of a core when the other is busy too: its one simulated second took five minutes in a loaded suite.
RUN_NICE = 2


@pytest.mark.skipif(not AUTOGROUPS, reason="this kernel has no autogroups")
def test_every_process_of_a_run_started_with_the_variable_runs_in_a_session_at_that_nice_value():
    own_autogroup = Path("/proc/self/autogroup").read_text()
    run = subprocess.Popen([sys.executable, "-m", "coopdrive.cli", "run", "platoon40", "--stacks", "2",
                            "--processes", "vehicle", "--duration", "1"],
                           stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL, start_new_session=True,
                           env={**os.environ, SESSION_NICE_VARIABLE: str(RUN_NICE)})
    # pid -> "autogroup nice N command", as last read: a process sets its session's value as its command starts
    seen: dict[int, str] = {}
    while run.poll() is None:
        for pid in _descendants(run.pid) | {run.pid}:
            try:
                command = Path(f"/proc/{pid}/cmdline").read_bytes().replace(b"\0", b" ").decode()
                if command:  # else the process has exited
                    seen[pid] = f"{Path(f'/proc/{pid}/autogroup').read_text().strip()} {command}"
            except OSError:
                continue
        # Each look reads every process's stat: looking 5 times a second catches the services (they live the whole
        # run) without taking the CPU the tests beside this one need.
        time.sleep(0.2)
    assert run.returncode == 0
    services = [line for line in seen.values() if "coopdrive group" in line or "coopdrive service" in line]
    assert len(services) >= 3, "\n".join(seen.values())  # the simulator's process and each stack's
    assert all(line.split()[1:3] == ["nice", str(RUN_NICE)] for line in seen.values()), seen
    # each service leads a session of its own, and none of them reniced the test's
    assert len({line.split()[0] for line in services}) == len(services)
    assert Path("/proc/self/autogroup").read_text() == own_autogroup
