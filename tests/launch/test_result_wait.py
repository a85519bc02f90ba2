"""The launcher waits for the simulator's result while a lagging recording still takes the run's messages."""

import threading
import time

import coopdrive.launch.run as run


class SimulatorExited:
    processes = {"world/sim": None, "ego/group": None}

    def exited(self) -> dict[str, int]:
        return {"world/sim": 0}


def test_a_result_behind_a_backlog_of_recorded_messages_is_still_waited_for(monkeypatch):
    monkeypatch.setattr(run, "RESULT_GRACE_S", 0.1)
    finished = threading.Event()
    started = time.monotonic()

    def recorded() -> int:
        """Messages keep coming for a second (the backlog), then the result."""
        elapsed_s = time.monotonic() - started
        if elapsed_s > 1.0:
            finished.set()
        return int(elapsed_s * 100)

    run._wait_for_the_end(SimulatorExited(), finished, recorded)
    assert finished.is_set()


def test_without_a_result_or_a_backlog_the_wait_ends_after_the_grace_period(monkeypatch):
    monkeypatch.setattr(run, "RESULT_GRACE_S", 0.1)
    finished = threading.Event()
    started = time.monotonic()
    run._wait_for_the_end(SimulatorExited(), finished, lambda: 7)
    assert not finished.is_set() and time.monotonic() - started < 1.0
