"""The localisation figures of a run, on hand-made truth, ego states and fixes with known errors."""

import math

import numpy as np
import pymap3d
import pytest

from coopdrive.judging.localisation import localisation_metrics
from coopdrive.judging.run_messages import RunMessages
from coopdrive.services.sim.truth_series import TruthSeries
from coopdrive.v1 import ego_pb2, gnss_pb2, sim_pb2

ORIGIN = (51.0, 5.0, 0.0)
SPEED_MPS = 10.0
OUTAGE_S = (2.0, 3.0)
JUMP_S = (4.0, 4.2)


def truth(duration_s=6.0) -> TruthSeries:
    frames = []
    for t in np.arange(0.0, duration_s + 1e-9, 0.1):
        frames.append((t, [sim_pb2.VehicleTruth(vehicle_id="ego", x_m=SPEED_MPS * t, y_m=0.0, lane_index=0,
                                                automated=True)]))
    return TruthSeries.from_frames(frames)


def ego_state(t, east_error_m, variance_m2=0.01, lane=0, mode=ego_pb2.LOCALISATION_MODE_GNSS_PRECISE):
    """lane None: matched to no lane."""
    state = ego_pb2.EgoState(x_m=SPEED_MPS * t + east_error_m, y_m=0.0, mode=mode,
                             last_fix_mode=gnss_pb2.FIX_MODE_RTK_FIXED)
    state.header.sample_time_s = t
    covariance = np.eye(6) * variance_m2
    state.covariance.extend(covariance.ravel())
    state.latitude_deg, state.longitude_deg, _ = pymap3d.enu2geodetic(state.x_m, state.y_m, 0.0, *ORIGIN)
    state.lane.matched, state.lane.lane_index = lane is not None, lane or 0
    return state


def fix(t, east_error_m, mode=gnss_pb2.FIX_MODE_RTK_FIXED, sigma_m=0.01):
    message = gnss_pb2.GnssFix(fix_mode=mode, std_east_m=sigma_m, std_north_m=sigma_m)
    message.header.sample_time_s = t
    if mode != gnss_pb2.FIX_MODE_NO_FIX:
        message.latitude_deg, message.longitude_deg, _ = pymap3d.enu2geodetic(
            SPEED_MPS * t + east_error_m, 0.0, 0.0, *ORIGIN)
    return message


def _messages(state_error, fix_error=lambda t: 0.02, lane=lambda t: 0) -> RunMessages:
    messages = RunMessages()
    for t in np.arange(0.0, 6.0, 0.02):
        messages.add("coopdrive/ego/ego/state", ego_state(t, state_error(t), lane=lane(t)))
    for t in np.arange(0.0, 6.0, 0.05):
        if OUTAGE_S[0] <= t < OUTAGE_S[1]:
            messages.add("coopdrive/ego/ego/gnss", fix(t, 0.0, gnss_pb2.FIX_MODE_NO_FIX))
        else:
            messages.add("coopdrive/ego/ego/gnss", fix(t, fix_error(t)))
    return messages


def run(state_error, fix_error=lambda t: 0.02, lane=lambda t: 0):
    return localisation_metrics(truth(), _messages(state_error, fix_error, lane))


def test_the_rms_errors_of_estimate_and_fixes_and_the_receivers_noise_are_measured():
    figures = run(state_error=lambda t: 0.005)
    assert figures["position_rmse_precise_m"] == pytest.approx(0.005, abs=1e-4)
    assert figures["gnss_fix_rmse_m"] == pytest.approx(0.02, abs=1e-4)
    assert figures["gnss_noise_rms_m"] == pytest.approx(math.hypot(0.01, 0.01))


def test_the_estimate_s_error_is_set_beside_the_raw_fixes_every_one_of_them_per_fix_mode():
    # A fix 3 m off is no longer left out of the fixes' RMS: no outlier is dropped silently.
    figures = localisation_metrics(truth(), _messages(lambda t: 0.005, lambda t: 3.0 if JUMP_S[0] <= t < JUMP_S[1]
                                                      else 0.02), position_rmse_m=0.005)
    fix_errors = np.array([3.0 if JUMP_S[0] <= t < JUMP_S[1] else 0.02 for t in np.arange(0.0, 6.0, 0.05)
                           if not OUTAGE_S[0] <= t < OUTAGE_S[1]])
    assert figures["gnss_fix_rmse_m"] == pytest.approx(np.sqrt(np.mean(fix_errors**2)), rel=1e-3)
    assert figures["gnss_fix_rmse_rtk_fixed_m"] == figures["gnss_fix_rmse_m"]
    assert figures["position_rmse_rtk_fixed_m"] == pytest.approx(0.005, abs=1e-4)
    assert figures["position_rmse_over_gnss_fix_rmse"] == pytest.approx(0.005 / figures["gnss_fix_rmse_m"])
    assert "gnss_fix_rmse_dgps_m" not in figures and "position_rmse_over_gnss_noise" not in figures


def test_the_2_sigma_share_counts_errors_inside_the_ellipse_of_their_covariance():
    # sigma 0.1 m: 0.19 m is NEES 3.61, inside the 2-sigma ellipse (NEES 4); 0.3 m is NEES 9, outside.
    figures = run(state_error=lambda t: 0.19 if t < 4.5 else 0.3)
    assert figures["position_2sigma_share"] == pytest.approx(4.5 / 6.0, abs=0.01)
    assert figures["position_nees_mean"] == pytest.approx((4.5 * 3.61 + 1.5 * 9.0) / 6.0, rel=0.01)


def test_the_nees_bounds_are_for_samples_a_second_apart_and_hold_the_nees_of_a_consistent_estimate():
    figures = run(state_error=lambda t: 0.1 * math.sqrt(2.0))
    assert figures["position_nees_samples_1hz"] == 6
    assert figures["position_nees_mean_1hz"] == pytest.approx(2.0)
    assert figures["position_nees_lower_95"] < 2.0 < figures["position_nees_upper_95"]


def test_the_outage_error_is_the_largest_while_the_receiver_reports_no_fix():
    figures = run(state_error=lambda t: 0.4 if OUTAGE_S[0] + 0.5 <= t < OUTAGE_S[0] + 0.6 else 0.01)
    assert figures["outage_position_error_max_m"] == pytest.approx(0.4)


def test_fixes_far_beyond_their_noise_are_a_jump_and_the_estimate_error_after_them_is_measured():
    figures = run(state_error=lambda t: 0.15 if JUMP_S[0] + 0.5 <= t < JUMP_S[0] + 0.6 else 0.01,
                  fix_error=lambda t: 5.0 if JUMP_S[0] <= t < JUMP_S[1] else 0.02)
    assert figures["gnss_jumps"] == 4
    assert figures["gnss_jump_position_error_max_m"] == pytest.approx(0.15)


def test_the_lane_index_accuracy_counts_matched_samples_on_the_true_lane():
    figures = run(state_error=lambda t: 0.01, lane=lambda t: 1 if 5.0 <= t < 5.6 else 0)
    assert figures["lane_index_accuracy"] == pytest.approx(1.0 - 0.6 / 6.0, abs=0.01)


def test_an_estimate_matched_to_no_lane_counts_as_a_wrong_lane():
    figures = run(state_error=lambda t: 0.01, lane=lambda t: None if 5.0 <= t < 5.6 else 0)
    assert figures["lane_index_accuracy"] == pytest.approx(1.0 - 0.6 / 6.0, abs=0.01)
