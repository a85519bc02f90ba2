"""Waiting for a live recorder: its subscription reaching the hub."""

import time

from coopdrive.bus import Bus

START_TIMEOUT_S = 60.0  # a loaded machine starts a Python service slowly; this catches a service that never comes


def wait_recording(hub: Bus, probe_key: str = "coopdrive/probe/nothing") -> None:
    """Until the recorder's subscription to everything reaches the hub (Zenoh's matching status says so)."""
    probe = hub.session.declare_publisher(probe_key)
    deadline = time.monotonic() + START_TIMEOUT_S
    try:
        while not probe.matching_status.matching:
            assert time.monotonic() < deadline, "the recorder did not subscribe"
            time.sleep(0.1)
    finally:
        probe.undeclare()
