"""A road log into a desk service, as a user does it: `coopdrive service geolocation --clock wall --set
vehicle_can=...RAV4 adapter`, fed by `python -m can.player -i coopdrive` playing the RAV4's candump log, over real
Zenoh sessions. The player keeps the log's timestamps (the logger's monotonic seconds): the service restamps them
on arrival and reports the car's speed, and counts the frames of the 81 ids the adapter does not use as ignored."""

import subprocess
import sys
import threading
import time

import pytest

from coopdrive.can.candump import CandumpLogger
from tests.can.rav4_drive import RAV4_ADAPTER, ground_truth, rav4_frames

VEHICLE = "rav4"
LOG_S = 2.0
WAIT_S = 30.0


@pytest.fixture
def geolocation_on_the_wall_clock(hub):
    _, endpoint = hub
    process = subprocess.Popen([sys.executable, "-m", "coopdrive.cli", "service", "geolocation", "--vehicle",
                                VEHICLE, "--connect", endpoint, "--clock", "wall",
                                "--set", f"vehicle_can={RAV4_ADAPTER}"],
                               stdout=subprocess.DEVNULL, stderr=subprocess.PIPE, text=True)
    yield process
    process.terminate()
    process.wait(timeout=WAIT_S)


def first_seconds_log(path):
    first_s = rav4_frames()[0].timestamp
    with CandumpLogger(path, channel="can0") as logger:
        logger.write_all(m for m in rav4_frames() if m.timestamp < first_s + LOG_S)


def wait_for(event: threading.Event, process: subprocess.Popen, what: str) -> None:
    deadline = time.monotonic() + WAIT_S
    while not event.wait(0.2):
        assert process.poll() is None, f"the service ended: {process.stderr.read()}"
        assert time.monotonic() < deadline, f"no {what} within {WAIT_S} s"


def test_can_player_feeding_a_wall_clock_geolocation_the_rav4_log_gives_the_car_s_speed(
        hub, geolocation_on_the_wall_clock, tmp_path):
    bus, endpoint = hub
    speeds, diagnostics = [], []
    running, moving, counted = threading.Event(), threading.Event(), threading.Event()

    def on_state(envelope) -> None:
        running.set()
        speeds.append(envelope.message.speed_mps)
        if envelope.message.speed_mps > 1.0:
            moving.set()

    def on_diagnostics(envelope) -> None:
        diagnostics.append(dict(envelope.message.counters))
        if moving.is_set() and envelope.message.counters.get("can_frames_restamped", 0) > 0:
            counted.set()

    bus.subscribe(VEHICLE, "ego/state", on_state)
    bus.subscribe(VEHICLE, "diagnostics/geolocation", on_diagnostics)
    wait_for(running, geolocation_on_the_wall_clock, "ego state")
    log = tmp_path / "rav4.log"
    first_seconds_log(log)
    completed = subprocess.run([sys.executable, "-m", "can.player", "-i", "coopdrive", "-c", VEHICLE,
                                f"--bus-kwargs=connect={endpoint}", str(log)],
                               capture_output=True, text=True, timeout=120)
    assert completed.returncode == 0, completed.stderr
    wait_for(moving, geolocation_on_the_wall_clock, "speed from the wheels")
    wait_for(counted, geolocation_on_the_wall_clock, "diagnostics")
    # The car accelerates through these two seconds: the last speed reported is comma's last mean wheel speed.
    truth = ground_truth("comma2k19_ground_truth_wheel_speed_first20s.csv")
    first_seconds = truth["t_s"] < rav4_frames()[0].timestamp + LOG_S
    assert max(speeds) == pytest.approx(truth["speed_mps"][first_seconds][-1], abs=0.05)
    counters = diagnostics[-1]
    assert counters["can_frames_received"] > 0 and counters["can_ids_ignored"] <= 81
    assert not [name for name in counters if name.startswith("can_rejected")]
