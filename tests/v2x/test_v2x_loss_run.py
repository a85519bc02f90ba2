"""Issue 5 in a run: two stacks behind a scripted leader with 20 % random V2V loss, then every link cut.
Each stack's v2x status reports its partners' reception at the channel's loss, and a partner silent for
400 ms as lost (the statistics the gateway serves under /state and /v2x/stations)."""

import json
import subprocess
import sys

import numpy as np
import pytest

from coopdrive.recording.reader import read_messages
from coopdrive.v1 import v2x_pb2
from tests.scenario_report import FASTEST_LAYOUT

pytestmark = pytest.mark.whole_run

LOSS = 0.2
CUT_AT_S = 10.0
LOSS_TIMEOUT_S = 0.4
PARTNERS = {"ego": (101, 103), "f2": (101, 102)}
SCENARIO = """
name: v2x_loss_pair
description: Two stacks behind a steady scripted leader, for the radio's statistics.
map: a270
seed: 5
duration_s: 12
step_s: 0.02
vehicles:
  - {vehicle_id: leader, station_id: 101, role: scripted, lane: 0, station_m: 200, speed_mps: 15.0}
  - {vehicle_id: ego, station_id: 102, lane: 0, station_m: 172, speed_mps: 15.0}
  - {vehicle_id: f2, station_id: 103, lane: 0, station_m: 144, speed_mps: 15.0}
"""


@pytest.fixture(scope="module")
def statuses(tmp_path_factory) -> dict[str, list[v2x_pb2.V2xStatus]]:
    folder = tmp_path_factory.mktemp("v2x_loss")
    (folder / "pair.yaml").write_text(SCENARIO)
    recording = folder / "run.mcap"
    result = subprocess.run([sys.executable, "-m", "coopdrive.cli", "run", str(folder / "pair.yaml"), "--json",
                             "--v2v-loss", str(LOSS), "--v2v-cut-at", str(CUT_AT_S), "--record", str(recording),
                             *FASTEST_LAYOUT],
                            capture_output=True, text=True, timeout=600)
    assert result.returncode in (0, 1), result.stderr
    assert json.loads(result.stdout)["collisions"] == 0
    by_vehicle: dict[str, list[v2x_pb2.V2xStatus]] = {}
    for item in read_messages(recording):
        if isinstance(item.message, v2x_pb2.V2xStatus):
            by_vehicle.setdefault(item.message.header.vehicle_id, []).append(item.message)
    return by_vehicle


def station(status: v2x_pb2.V2xStatus, station_id: int) -> v2x_pb2.StationLinkStats | None:
    return next((s for s in status.stations if s.station_id == station_id), None)


def test_each_partner_s_reception_ratio_is_the_channel_s_within_a_few_percent(statuses):
    for vehicle, partners in PARTNERS.items():
        # The statistics window is 5 s: judge it once full, before the cut.
        steady = [s for s in statuses[vehicle] if 5.5 <= s.header.sample_time_s < CUT_AT_S]
        for partner in partners:
            ratio = np.mean([station(s, partner).reception_ratio for s in steady])
            assert ratio == pytest.approx(1.0 - LOSS, abs=0.04), (vehicle, partner)


def test_a_partner_silent_for_400_ms_is_reported_lost_and_not_before(statuses):
    for vehicle, partners in PARTNERS.items():
        for partner in partners:
            after_cut = [(s.header.sample_time_s, station(s, partner)) for s in statuses[vehicle]
                         if s.header.sample_time_s >= CUT_AT_S and station(s, partner) is not None]
            lost_at_s = next(t for t, link in after_cut if link.state == v2x_pb2.LINK_STATE_LOST)
            last_heard_s = max(link.last_heard_s for _, link in after_cut)
            assert LOSS_TIMEOUT_S <= lost_at_s - last_heard_s <= LOSS_TIMEOUT_S + 0.15, (vehicle, partner)
            assert all(link.state == v2x_pb2.LINK_STATE_ACTIVE for t, link in after_cut
                       if t < last_heard_s + LOSS_TIMEOUT_S - 1e-6)
