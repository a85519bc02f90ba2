import numpy as np
import pytest

from coopdrive.services.v2x.config import PlausibilityLimits
from coopdrive.services.v2x.reception import OwnIdentity, Reception
from coopdrive.v1 import its_pb2, v2x_pb2

from .streams import CLOCK, REMOTE_MAC, REMOTE_STATION_ID, cam_packet, remote_cam

OWN = OwnIdentity(mac=bytes.fromhex("020000000001"), station_id=1001)
PERIOD_S = 0.04
DELAY_S = 0.005


def reception(window_s: float = 60.0) -> Reception:
    return Reception(OWN, CLOCK, PlausibilityLimits(), loss_timeout_s=0.4, expected_rate_hz=25.0, window_s=window_s)


def receive(rx: Reception, generation_s: float, receive_s: float | None = None, mac: bytes = REMOTE_MAC, **cam):
    content = remote_cam(generation_s, **cam)
    receive_s = generation_s + DELAY_S if receive_s is None else receive_s
    return rx.on_packet(cam_packet(content, generation_s, mac), receive_s).decoded


def station(status: v2x_pb2.V2xStatus, station_id: int = REMOTE_STATION_ID) -> v2x_pb2.StationLinkStats:
    return next(s for s in status.stations if s.station_id == station_id)


def test_reception_ratio_rate_and_delays_match_a_25_hz_stream_with_20_percent_random_loss():
    rng = np.random.default_rng(2016)
    rx = reception()
    kept = 0
    jitter_s = rng.uniform(0.0, 0.01, size=1000)
    for index in range(1000):
        if rng.random() < 0.2:
            continue
        kept += 1
        generation_s = index * PERIOD_S
        assert receive(rx, generation_s, generation_s + DELAY_S + jitter_s[index]) is not None
    stats = station(rx.status(999 * PERIOD_S + DELAY_S))
    assert kept / 1000 == pytest.approx(0.8, abs=0.03)
    assert stats.reception_ratio == pytest.approx(kept / 1000, abs=0.02)
    assert stats.message_rate_hz == pytest.approx(25.0 * kept / 1000, rel=0.03)
    assert stats.update_delay_p50_s == pytest.approx(0.01, abs=0.002)
    assert 0.013 <= stats.update_delay_p95_s <= stats.update_delay_max_s <= 0.016
    assert stats.state == v2x_pb2.LINK_STATE_ACTIVE
    assert stats.messages_received == kept and stats.messages_rejected == 0


def test_a_lossless_stream_has_a_reception_ratio_of_one():
    rx = reception()
    for index in range(100):
        receive(rx, index * PERIOD_S)
    assert station(rx.status(4.0)).reception_ratio == pytest.approx(1.0)


def test_a_station_is_lost_after_400_ms_of_silence_and_active_again_when_heard():
    rx = reception()
    for index in range(25):
        receive(rx, index * PERIOD_S)
    last_heard_s = 24 * PERIOD_S + DELAY_S
    assert station(rx.status(last_heard_s + 0.39)).state == v2x_pb2.LINK_STATE_ACTIVE
    lost = station(rx.status(last_heard_s + 0.41))
    assert lost.state == v2x_pb2.LINK_STATE_LOST
    assert lost.last_heard_s == pytest.approx(last_heard_s)
    receive(rx, 2.0)
    assert station(rx.status(2.01)).state == v2x_pb2.LINK_STATE_ACTIVE


@pytest.mark.parametrize("reason, bad_cam", [
    ("position_jump", dict(north_m=120.0)),
    ("implausible_speed", dict(speed_mps=90.0)),
    ("implausible_acceleration", dict(accel_mps2=25.0)),
    ("implausible_acceleration", dict(speed_mps=30.0)),
])
def test_implausible_kinematics_are_rejected_and_counted_by_reason(reason, bad_cam):
    rx = reception()
    assert receive(rx, 0.0) is not None
    assert receive(rx, PERIOD_S, **bad_cam) is None
    assert receive(rx, 2 * PERIOD_S) is not None
    status = rx.status(0.1)
    assert dict(status.rejected_by_reason) == {reason: 1}
    assert (station(status).messages_received, station(status).messages_rejected) == (2, 1)


@pytest.mark.parametrize("reason, generation_s, receive_s", [
    ("too_old", 0.0, 1.5),
    ("from_the_future", 1.0, 0.5),
])
def test_messages_too_old_or_from_the_future_are_rejected(reason, generation_s, receive_s):
    rx = reception()
    assert receive(rx, generation_s, receive_s) is None
    assert dict(rx.status(receive_s).rejected_by_reason) == {reason: 1}


def test_a_duplicate_or_reordered_message_is_rejected_as_not_newer():
    rx = reception()
    receive(rx, 0.08)
    assert receive(rx, 0.08, 0.09) is None
    assert receive(rx, 0.04, 0.095) is None
    assert dict(rx.status(0.1).rejected_by_reason) == {"not_newer": 2}


def test_a_station_id_changing_mid_stream_for_the_same_mac_is_rejected_but_allowed_after_a_silence():
    rx = reception()
    receive(rx, 0.0)
    assert receive(rx, PERIOD_S, station_id=3003) is None
    assert dict(rx.status(0.1).rejected_by_reason) == {"station_id_changed": 1}
    assert receive(rx, 1.0, station_id=3003) is not None


def test_our_own_packets_looped_back_by_the_radio_are_ignored_by_mac_or_station_id():
    rx = reception()
    assert receive(rx, 0.0, mac=OWN.mac) is None
    assert receive(rx, 0.04, station_id=OWN.station_id) is None
    status = rx.status(0.1)
    assert rx.own_packets_ignored == 2
    assert list(status.stations) == [] and dict(status.rejected_by_reason) == {}


def test_undecodable_packets_are_counted_by_the_decoder_reason():
    rx = reception()
    assert rx.on_packet(b"\x00", 0.0).decoded is None
    assert rx.on_packet(bytes([0x20]) + bytes(60), 0.0).decoded is None
    status = rx.status(0.1)
    assert dict(status.rejected_by_reason) == {"truncated_basic_header": 1, "unsupported_gn_version": 1}
    assert status.packets_received == 2


def test_an_accepted_cam_is_returned_decoded():
    decoded = receive(reception(), 0.0)
    assert decoded.station_id == REMOTE_STATION_ID
    assert decoded.content.high_frequency.speed_mps == pytest.approx(20.0)
    assert decoded.content.station_type == its_pb2.STATION_TYPE_PASSENGER_CAR


def test_a_station_silent_for_a_minute_leaves_the_status_even_if_it_only_sent_rejected_packets():
    rx = reception()
    receive(rx, 0.0)
    receive(rx, 0.5, station_id=4004, speed_mps=99.0)
    assert {s.station_id for s in rx.status(1.0).stations} == {REMOTE_STATION_ID}
    assert set(rx.stations) == {REMOTE_STATION_ID, 4004}
    rx.status(61.0)
    assert rx.stations == {}


def test_a_station_whose_first_position_was_wrong_is_followed_again_after_one_rejected_message():
    rx = reception()
    assert receive(rx, 0.0) is not None
    for index in range(1, 6):
        received = receive(rx, index * PERIOD_S, north_m=300.0 + index)
        assert (received is None) == (index == 1)
    assert dict(rx.status(0.3).rejected_by_reason) == {"position_jump": 1}


def test_a_stream_s_totals_since_first_heard_survive_the_window_after_its_sender_stops():
    rx = reception(window_s=5.0)
    kept = 0
    for index in range(100):
        if index % 10 != 3:
            receive(rx, index * PERIOD_S)
            kept += 1
    stats = station(rx.status(60.0))
    assert stats.reception_ratio == 0.0
    assert (stats.periodic_received_total, stats.periodic_expected_total) == (kept, 100)


def test_what_reception_heard_carries_the_sender_s_mac_and_the_transit_delay_so_nobody_reads_the_packet_again():
    rx = reception()
    generation_s = 3.0
    heard = rx.on_packet(cam_packet(remote_cam(generation_s), generation_s, REMOTE_MAC), generation_s + 0.02)
    assert heard.source_mac == REMOTE_MAC
    assert heard.decoded.station_id == REMOTE_STATION_ID
    assert heard.transit_delay_s == pytest.approx(0.02, abs=1e-3)
    assert heard.generated_s == pytest.approx(generation_s, abs=1e-3)
    undecodable = rx.on_packet(b"\x00", 4.0)
    assert (undecodable.source_mac, undecodable.decoded, undecodable.generated_s) == (None, None, 4.0)
