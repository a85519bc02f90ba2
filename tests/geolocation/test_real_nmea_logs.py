"""Issue 24, item 7: geolocation over the four real receivers' NMEA logs of shared/data/gnss (gpsd's corpus), replayed
as `coopdrive replay` does a recording of gnss/nmea (chunks stamped with the receiver's UTC)."""

import datetime
import logging
import math

import numpy as np
import pymap3d
import pytest

from coopdrive.services.geolocation.service import GeolocationConfig
from coopdrive.v1 import ego_pb2
from tests.geolocation.nmea_replay import replay_nmea_log
from tests.shared_data import shared_file

LOGS = ["gpsd_bundg_zeus_9.log", "gpsd_hemi.log", "gpsd_quectel-eg25-g.log", "gpsd_ublox-neo-m9n-nmea.log"]
LOST = ego_pb2.LOCALISATION_MODE_LOST
# 10 Hz estimates instead of 50: the same filter, a fifth of the test's time.
CONFIG = GeolocationConfig(output_rate_hz=10.0)
MOVING_MPS = 1.0


@pytest.fixture(scope="module")
def replays():
    return {name: replay_nmea_log(shared_file(f"gnss/{name}"), CONFIG) for name in LOGS}


def distance_m(state, fix) -> float:
    east_m, north_m, _ = pymap3d.geodetic2enu(state.latitude_deg, state.longitude_deg, 0.0,
                                              fix.latitude_deg, fix.longitude_deg, 0.0)
    return math.hypot(east_m, north_m)


def estimates_after_each_fix(replay):
    """For each fix with a position: the first estimate published once the fix was decoded."""
    return [(fix, replay.state_at_or_after(fix.header.sent_time_s)) for fix in replay.position_fixes]


@pytest.mark.parametrize("name", LOGS)
def test_every_log_gives_a_position_that_is_not_lost_within_2_s_of_its_first_fix(replays, name):
    replay = replays[name]
    first_fix_s = replay.position_fixes[0].header.sample_time_s
    first_position = next(s for s in replay.states if s.mode != LOST)
    assert first_position.header.sample_time_s - first_fix_s <= 2.0


def test_on_the_moving_boat_every_fix_has_an_estimate_the_first_within_1_5_m_of_the_first_gga(replays):
    replay = replays["gpsd_bundg_zeus_9.log"]
    pairs = estimates_after_each_fix(replay)
    assert len(pairs) == 138  # every GGA of the log
    assert all(state is not None and state.mode != LOST for _, state in pairs)
    first_fix, first_state = pairs[0]
    assert (first_fix.latitude_deg, first_fix.longitude_deg) == pytest.approx((52.850157, 5.313620), abs=1e-6)
    assert distance_m(first_state, first_fix) < 1.5


def test_on_the_moving_boat_the_speed_is_within_0_3_mps_of_rmc_speed_over_ground(replays):
    pairs = estimates_after_each_fix(replays["gpsd_bundg_zeus_9.log"])
    errors_mps = np.array([state.speed_mps - fix.speed_mps for fix, state in pairs
                           if fix.velocity_valid and fix.speed_mps > MOVING_MPS])
    assert len(errors_mps) > 130
    assert np.max(np.abs(errors_mps)) < 0.3


def test_the_hemisphere_heading_follows_its_dual_antenna_hdt_within_1_degree(replays):
    pairs = [(fix, state) for fix, state in estimates_after_each_fix(replays["gpsd_hemi.log"]) if fix.heading_valid]
    assert [round(fix.heading_deg, 2) for fix, _ in pairs] == [274.07, 274.04, 274.12, 274.11]
    for fix, state in pairs:
        heading_deg = 90.0 - math.degrees(state.heading_rad)  # ENU radians -> from north, clockwise
        assert abs((heading_deg - fix.heading_deg + 180.0) % 360.0 - 180.0) < 1.0


def test_a_standing_receiver_is_never_lost_and_stands_still_with_its_heading_unknown(replays):
    replay = replays["gpsd_ublox-neo-m9n-nmea.log"]
    assert all(state.mode != LOST for state in replay.states)
    assert max(abs(state.speed_mps) for state in replay.states) < 0.1  # RMC says 0.006-0.084 kn
    heading_std_rad = math.sqrt(np.array(replay.states[-1].covariance).reshape(6, 6)[2, 2])
    assert heading_std_rad > 2.0  # no heading from a receiver that does not move: still all but unknown
    assert all(state.mode == ego_pb2.LOCALISATION_MODE_GNSS_DEGRADED for _, state in estimates_after_each_fix(replay))


def test_fix_times_come_from_the_nmea_utc_and_the_log_s_gaps_are_counted(replays):
    replay = replays["gpsd_bundg_zeus_9.log"]
    first = datetime.datetime.fromtimestamp(replay.position_fixes[1].utc_time_s, datetime.timezone.utc)
    assert first == datetime.datetime(2018, 8, 20, 9, 47, 37, tzinfo=datetime.timezone.utc)
    steps_s = np.diff([fix.utc_time_s for fix in replay.position_fixes[1:]])
    assert replay.service.counters["nmea_epoch_gaps"] == np.count_nonzero(steps_s > 1.5) > 0


def test_the_first_fix_is_the_origin_of_the_local_frame_when_none_is_configured(replays):
    replay = replays["gpsd_ublox-neo-m9n-nmea.log"]
    first_fix = replay.position_fixes[0]
    assert replay.service.geolocator.origin[:2] == (first_fix.latitude_deg, first_fix.longitude_deg)
    assert max(math.hypot(s.x_m, s.y_m) for s in replay.states if s.mode != LOST) < 5.0


def test_a_configured_origin_far_from_the_fixes_is_refused_in_one_line_naming_the_distance(caplog):
    # Boston's fixes against the default origin of the simulated world, in the Netherlands.
    config = GeolocationConfig(output_rate_hz=2.0, origin={"lat_deg": 51.4758, "lon_deg": 5.6247})
    with caplog.at_level(logging.ERROR):
        replay = replay_nmea_log(shared_file("gnss/gpsd_hemi.log"), config)
    errors = [record.getMessage() for record in caplog.records if record.levelno >= logging.ERROR]
    assert len(errors) == 1 and "\n" not in errors[0]
    assert "5653 km" in errors[0] and "refused" in errors[0]
    assert replay.service.counters["input_fix_far_from_origin"] == 21
    assert all(state.mode == LOST for state in replay.states)
