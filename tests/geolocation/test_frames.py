import math

import pytest

from coopdrive.services.geolocation.frames import LeverArm, ModeThresholds, localisation_mode
from coopdrive.v1 import ego_pb2, gnss_pb2

THRESHOLDS = ModeThresholds(precise_std_m=0.3, lost_std_m=5.0, gnss_timeout_s=0.5)


def test_an_antenna_ahead_of_the_rear_axle_is_ahead_along_the_heading():
    arm = LeverArm(x_m=2.0, y_m=0.5)
    assert arm.antenna_position(10.0, 20.0, math.pi / 2) == pytest.approx((9.5, 22.0))
    assert arm.rear_axle_position(9.5, 22.0, math.pi / 2) == pytest.approx((10.0, 20.0))


def test_the_lever_arm_jacobian_matches_a_finite_difference():
    arm, heading, step = LeverArm(1.5, -0.3), 0.7, 1e-6
    ahead, behind = arm.antenna_position(0, 0, heading + step), arm.antenna_position(0, 0, heading - step)
    numeric = [(a - b) / (2 * step) for a, b in zip(ahead, behind)]
    assert arm.d_antenna_d_heading(heading) == pytest.approx(numeric, rel=1e-6)


@pytest.mark.parametrize(("initialised", "std_m", "since_fix_s", "fix_mode", "mode"), [
    (False, 0.01, 0.0, gnss_pb2.FIX_MODE_RTK_FIXED, ego_pb2.LOCALISATION_MODE_LOST),
    (True, 0.02, 0.05, gnss_pb2.FIX_MODE_RTK_FIXED, ego_pb2.LOCALISATION_MODE_GNSS_PRECISE),
    (True, 0.2, 0.05, gnss_pb2.FIX_MODE_RTK_FLOAT, ego_pb2.LOCALISATION_MODE_GNSS_PRECISE),
    (True, 0.2, 0.05, gnss_pb2.FIX_MODE_DGPS, ego_pb2.LOCALISATION_MODE_GNSS_DEGRADED),
    (True, 0.6, 0.05, gnss_pb2.FIX_MODE_RTK_FLOAT, ego_pb2.LOCALISATION_MODE_GNSS_DEGRADED),
    (True, 0.6, 2.0, gnss_pb2.FIX_MODE_RTK_FIXED, ego_pb2.LOCALISATION_MODE_DEAD_RECKONING),
    (True, 6.0, 2.0, gnss_pb2.FIX_MODE_RTK_FIXED, ego_pb2.LOCALISATION_MODE_LOST),
])
def test_the_localisation_mode_follows_fix_mode_age_and_covariance(initialised, std_m, since_fix_s, fix_mode, mode):
    assert localisation_mode(initialised, std_m, since_fix_s, fix_mode, THRESHOLDS) == mode
