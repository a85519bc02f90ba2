"""Once the simulator has exited, the launcher waits RESULT_GRACE_S for its result, then returns without one."""

import threading
import time

import coopdrive.launch.run as run

GRACE_S = 0.5


class SimulatorExited:
    processes = {"world/sim": None, "ego/group": None}
    process_of = {"world/sim": "world/sim", "ego/control": "ego/group"}

    def exited(self) -> dict[str, int]:
        return {"world/sim": 0}


def test_a_result_that_comes_within_the_grace_period_after_the_simulator_exited_is_waited_for(monkeypatch):
    monkeypatch.setattr(run, "RESULT_GRACE_S", GRACE_S)
    finished = threading.Event()
    threading.Timer(GRACE_S / 2, finished.set).start()
    run._wait_for_the_end(SimulatorExited(), finished)
    assert finished.is_set()


def test_without_a_result_the_wait_ends_after_the_grace_period(monkeypatch):
    monkeypatch.setattr(run, "RESULT_GRACE_S", GRACE_S)
    finished = threading.Event()
    started = time.monotonic()
    run._wait_for_the_end(SimulatorExited(), finished)
    waited_s = time.monotonic() - started
    assert not finished.is_set() and waited_s >= GRACE_S
