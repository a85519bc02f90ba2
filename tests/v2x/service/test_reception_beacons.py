"""The receive path hears a real stack's GN beacons (FlexStack capture): positions by MAC, no rejection."""

import pytest

from coopdrive.recording.capture import read_gn_packets
from coopdrive.services.v2x.config import PlausibilityLimits
from coopdrive.services.v2x.reception import OwnIdentity, Reception
from tests.shared_data import shared_file

from .streams import CLOCK

OWN = OwnIdentity(mac=bytes.fromhex("020000000001"), station_id=1001)
FLEXSTACK_MAC = bytes.fromhex("dd1408c7c001")


def test_beacons_of_a_real_capture_update_the_neighbour_positions_and_are_not_rejections():
    reception = Reception(OWN, CLOCK, PlausibilityLimits(), loss_timeout_s=0.4, expected_rate_hz=10.0, window_s=60.0)
    frames = list(read_gn_packets(shared_file("v2x/flexstack_cam_vam_beacons.pcap")))
    start_s = frames[0].time_s
    beacons = [frame for frame in frames if frame.gn_packet[5] >> 4 == 1]  # common header type 1
    for frame in beacons:
        assert reception.on_packet(frame.gn_packet, frame.time_s - start_s).decoded is None
    assert reception.beacons_received == len(beacons) == 9
    assert dict(reception.rejected_by_reason) == {}
    position = reception.beacon_positions[FLEXSTACK_MAC]
    assert position.latitude_deg == pytest.approx(41.387, abs=0.01)
    assert position.receive_s == pytest.approx(beacons[-1].time_s - start_s)


def test_our_own_beacon_heard_back_is_ignored():
    reception = Reception(OwnIdentity(FLEXSTACK_MAC, 1), CLOCK, PlausibilityLimits(), 0.4, 10.0, 60.0)
    beacon = next(f for f in read_gn_packets(shared_file("v2x/flexstack_cam_vam_beacons.pcap"))
                  if f.gn_packet[5] >> 4 == 1)
    reception.on_packet(beacon.gn_packet, 0.0)
    assert (reception.beacons_received, reception.own_packets_ignored, reception.beacon_positions) == (0, 1, {})
