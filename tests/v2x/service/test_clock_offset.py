"""A station whose clock runs off ours: its offset and a likely cause in the station table (so a peer stamping UTC
since 2004 instead of TAI is named, not silently refused as too old), and a setting to accept a known offset."""

import numpy as np
import pytest

from coopdrive.services.v2x.clock_offset import ClockOffset, diagnose
from coopdrive.services.v2x.config import PlausibilityLimits
from coopdrive.services.v2x.reception import OwnIdentity, Reception
from coopdrive.v2x.timebase import ItsClock

from .streams import CLOCK, EPOCH_UNIX_S, REMOTE_STATION_ID, cam_packet, remote_cam

OWN = OwnIdentity(mac=bytes.fromhex("020000000001"), station_id=1001)
DELAY_S = 0.01
# The leap seconds since 2004 on the GCDC weekend of streams.EPOCH_UNIX_S (2016): 2005, 2008, 2012 and 2015.
LEAP_SECONDS_2016 = 4
UTC_STAMPING = ItsClock(EPOCH_UNIX_S - LEAP_SECONDS_2016)


def reception(**known) -> Reception:
    return Reception(OWN, CLOCK, PlausibilityLimits(), loss_timeout_s=0.4, expected_rate_hz=None, window_s=5.0,
                     known_clock_offsets_s=known.get("offsets"))


def hear_from_a_station_stamping(rx: Reception, clock: ItsClock, seconds: float = 3.0) -> float:
    for generation_s in np.arange(0.0, seconds, 0.1):
        content = remote_cam(generation_s, clock=clock)
        rx.on_packet(cam_packet(content, generation_s, clock=clock), generation_s + DELAY_S)
    return seconds


def test_a_station_stamping_utc_since_2004_is_listed_with_its_offset_and_the_leap_seconds_named():
    rx = reception()
    now_s = hear_from_a_station_stamping(rx, UTC_STAMPING)
    status = rx.status(now_s)
    assert status.rejected_by_reason["too_old"] == 30
    station = next(s for s in status.stations if s.station_id == REMOTE_STATION_ID)
    assert station.clock_offset_s == pytest.approx(-LEAP_SECONDS_2016 - DELAY_S, abs=1e-3)
    assert station.clock_diagnostic == (f"its clock is {LEAP_SECONDS_2016} s behind ours: it stamps UTC since 2004 "
                                        f"without the {LEAP_SECONDS_2016} leap seconds since (TimestampIts is TAI, "
                                        "TS 102 894-2)")
    assert station.messages_received == 0


def test_a_known_constant_offset_is_accepted_and_its_cams_are_heard():
    rx = reception(offsets={REMOTE_STATION_ID: -float(LEAP_SECONDS_2016)})
    now_s = hear_from_a_station_stamping(rx, UTC_STAMPING)
    status = rx.status(now_s)
    station = next(s for s in status.stations if s.station_id == REMOTE_STATION_ID)
    assert station.messages_received == 30 and "too_old" not in status.rejected_by_reason
    assert station.update_delay_p50_s == pytest.approx(DELAY_S, abs=1e-3)


def test_a_synchronised_station_shows_only_its_transit_and_no_diagnostic():
    rx = reception()
    now_s = hear_from_a_station_stamping(rx, CLOCK)
    station = next(s for s in rx.status(now_s).stations if s.station_id == REMOTE_STATION_ID)
    assert station.clock_offset_s == pytest.approx(-DELAY_S, abs=1e-3) and station.clock_diagnostic == ""


@pytest.mark.parametrize("offset_s, cause", [
    (-5.004, "5 s behind ours: it stamps UTC since 2004 without the 5 leap seconds"),
    (-19.01, "19 s behind ours: it stamps GPS time, which runs 19 s behind TAI"),
    (3.0, "3 s ahead of ours: a whole number of seconds: likely another time scale than TAI"),
    (-2.4, "2.4 s behind ours: not synchronised"),
])
def test_each_offset_is_given_its_likely_cause(offset_s, cause):
    assert cause in diagnose(offset_s, leap_seconds_since_2004=5)


def test_the_offset_is_a_median_that_one_late_packet_does_not_move():
    clock = ClockOffset()
    for _ in range(5):
        clock.add(generation_tai_ms=1000, receive_tai_ms=1010)
    clock.add(generation_tai_ms=1000, receive_tai_ms=1900)
    assert clock.offset_s() == pytest.approx(-0.010)
