"""`coopdrive v2x decode CAPTURE --json` shows a MAPEM's lanes and a SPATEM's signal-group states: on the real
signed capture of shared/data/v2x, and on a capture of messages another encoder (asn1tools) wrote."""

import json
import subprocess
import sys

import pytest

from coopdrive.v2x.btp import BtpPort
from coopdrive.v2x.pcap import PcapWriter
from tests.shared_data import shared_file
from tests.v2x import infrastructure_messages as messages

CAPTURE_TIME_S = 1_700_000_000.0


def decode(path, *options: str) -> list[str]:
    result = subprocess.run([sys.executable, "-m", "coopdrive.cli", "v2x", "decode", str(path), *options],
                            capture_output=True, text=True, timeout=120, check=True)
    return result.stdout.splitlines()


def test_the_real_spatem_shows_each_signal_groups_state_and_end_time_in_the_json():
    records = [json.loads(line) for line in decode(shared_file("v2x/considerit_signed_testvectors.pcap"), "--json")]
    spatem = records[3]
    (intersection,) = spatem["content"]["intersections"]
    assert intersection["id"] == {"region": 30, "id": 63}
    first = intersection["signal_groups"][0]
    assert (first["signal_group"], first["events"][0]["state"], first["events"][0]["min_end_time_s"]) == \
        (1, "MOVEMENT_PHASE_STATE_STOP_AND_REMAIN", pytest.approx(1636.0))
    assert len(intersection["signal_groups"]) == 25 and spatem["security"]["verified"] is True


@pytest.fixture
def capture(tmp_path):
    path = tmp_path / "rsu.pcap"
    with path.open("wb") as stream:
        writer = PcapWriter(stream, messages.RSU_MAC)
        for offset_s, kind, value in ((0.0, "MAPEM", messages.mapem(1)), (0.1, "SPATEM", messages.spatem(2))):
            writer.write(messages.gn_packet(BtpPort[kind], messages.encoded(kind, value)), CAPTURE_TIME_S + offset_s)
    return path


def test_a_capture_of_another_encoders_mapem_and_spatem_shows_the_lanes_with_their_nodes_and_the_states(capture):
    mapem, spatem, summary = (json.loads(line) for line in decode(capture, "--json"))
    lanes = mapem["content"]["intersections"][0]["lanes"]
    assert (mapem["message_type"], [lane["lane_id"] for lane in lanes]) == ("mapem", [1, 2])
    assert lanes[0]["nodes"][0] == {"east_m": pytest.approx(-1.5), "north_m": pytest.approx(0.2)}
    assert lanes[0]["connections"][0] == {"to_lane_id": 5, "signal_group": 4, "connection_id": 9}
    groups = spatem["content"]["intersections"][0]["signal_groups"]
    assert [(group["signal_group"], group["events"][0]["state"]) for group in groups] == \
        [(4, "MOVEMENT_PHASE_STATE_PROTECTED_MOVEMENT_ALLOWED"), (2, "MOVEMENT_PHASE_STATE_STOP_AND_REMAIN")]
    assert "error" not in mapem and "error" not in spatem and "summary" in summary


def test_the_text_listing_names_each_intersection_with_its_lane_count_or_its_signal_groups_phases(capture):
    mapem, spatem = decode(capture)[:2]
    assert mapem.endswith("mapem station 777 intersection 1234: 2 lanes")
    assert spatem.endswith("spatem station 777 intersection 1234: 4=protected_movement_allowed 2=stop_and_remain")
