"""Reception ratios per station at the rate it really sends: a profile's fixed rate (GCDC's 25 Hz), or, for a
standard station whose CAM generation rules (EN 302 637-2, 6.1.3) give 1-10 Hz, the station's own."""

import numpy as np
import pytest

from coopdrive.services.v2x.config import CamMode, PlausibilityLimits, V2xConfig
from coopdrive.v2x.expected_period import FixedPeriod, ObservedPeriod
from coopdrive.services.v2x.reception import OwnIdentity, Reception
from coopdrive.v1 import v2x_pb2

from .streams import CLOCK, REMOTE_STATION_ID, cam_packet, remote_cam

OWN = OwnIdentity(mac=bytes.fromhex("020000000001"), station_id=1001)
DELAY_S = 0.005
WINDOW_S = 60.0
# The v2x service's default statistics window.
DEFAULT_WINDOW_S = V2xConfig().statistics_window_s


def reception(expected_rate_hz: float | None, window_s: float = WINDOW_S) -> Reception:
    return Reception(OWN, CLOCK, PlausibilityLimits(), loss_timeout_s=1.5, expected_rate_hz=expected_rate_hz,
                     window_s=window_s)


def station(rx: Reception, now_s: float) -> v2x_pb2.StationLinkStats:
    return next(s for s in rx.status(now_s).stations if s.station_id == REMOTE_STATION_ID)


def send(rx: Reception, generation_times_s) -> float:
    for generation_s in generation_times_s:
        rx.on_packet(cam_packet(remote_cam(generation_s, speed_mps=15.0), generation_s), generation_s + DELAY_S)
    return generation_times_s[-1] + DELAY_S


def test_a_healthy_10_hz_standard_station_shows_a_reception_ratio_of_one_and_its_rate():
    rx = reception(expected_rate_hz=None)
    now_s = send(rx, np.arange(0.0, 20.0, 0.1))
    stats = station(rx, now_s)
    assert stats.reception_ratio == pytest.approx(1.0)
    assert stats.expected_cam_rate_hz == pytest.approx(10.0)


def test_judged_at_gcdc_s_25_hz_the_same_station_would_show_half():
    rx = reception(expected_rate_hz=25.0)
    now_s = send(rx, np.arange(0.0, 20.0, 0.1))
    assert station(rx, now_s).reception_ratio == pytest.approx(0.5, abs=0.02)


def test_a_10_hz_station_losing_a_fifth_of_its_cams_shows_about_four_fifths():
    rng = np.random.default_rng(637)
    times = [t for t in np.arange(0.0, 60.0, 0.1) if rng.random() >= 0.2]
    rx = reception(expected_rate_hz=None)
    now_s = send(rx, times)
    assert station(rx, now_s).reception_ratio == pytest.approx(len(times) / 600, abs=0.03)


def test_a_station_that_slows_from_10_hz_to_1_hz_is_followed_within_a_few_of_its_slow_gaps():
    rx = reception(expected_rate_hz=None, window_s=DEFAULT_WINDOW_S)
    send(rx, np.arange(0.0, 10.0, 0.1))
    now_s = send(rx, np.arange(10.0, 30.0, 1.0))
    stats = station(rx, now_s)
    assert stats.expected_cam_rate_hz == pytest.approx(1.0)
    assert stats.reception_ratio == pytest.approx(1.0)


def test_the_gcdc_profile_expects_25_hz_and_the_etsi_profile_each_station_s_own_unless_a_rate_is_set():
    assert V2xConfig(profile="gcdc").cam_mode is CamMode.GCDC and V2xConfig(profile="gcdc").expected_rate_hz == 25.0
    assert V2xConfig(cam_mode="gcdc").expected_rate_hz == 25.0
    assert V2xConfig().expected_rate_hz is None and V2xConfig(cam_mode="etsi").expected_rate_hz is None
    assert V2xConfig(cam_mode="etsi", expected_rate_hz=10.0).expected_rate_hz == 10.0


def test_the_observed_period_is_the_median_gap_and_rides_over_a_lost_message():
    period = ObservedPeriod()
    assert period.period_ms() is None
    for gap_ms in (100, 100, 200, 100, 100):
        period.observe(gap_ms)
    assert period.period_ms() == 100
    assert FixedPeriod(25.0).period_ms() == 40.0


def active_after_silence(rx: Reception, last_heard_s: float, silence_s: float) -> bool:
    return station(rx, last_heard_s + silence_s).state == v2x_pb2.LINK_STATE_ACTIVE


def test_a_2_5_hz_standard_station_stays_active_between_its_cams_and_is_lost_after_three_missed():
    rx = Reception(OWN, CLOCK, PlausibilityLimits(), loss_timeout_s=V2xConfig().loss_timeout_s, expected_rate_hz=None,
                   window_s=DEFAULT_WINDOW_S)
    last_heard_s = send(rx, np.arange(0.0, 10.0, 0.4))
    assert active_after_silence(rx, last_heard_s, 0.6)  # past the 0.4 s setting, one CAM missed
    assert active_after_silence(rx, last_heard_s, 1.1)
    assert not active_after_silence(rx, last_heard_s, 1.3)  # three of its 400 ms periods


def test_at_gcdc_s_25_hz_the_setting_decides_when_a_station_is_lost():
    rx = Reception(OWN, CLOCK, PlausibilityLimits(), loss_timeout_s=V2xConfig().loss_timeout_s, expected_rate_hz=25.0,
                   window_s=DEFAULT_WINDOW_S)
    last_heard_s = send(rx, np.arange(0.0, 5.0, 0.04))
    assert active_after_silence(rx, last_heard_s, 0.35)
    assert not active_after_silence(rx, last_heard_s, 0.45)
