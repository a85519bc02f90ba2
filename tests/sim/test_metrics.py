import math

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from coopdrive.services.sim import geometry, metrics, string_gain
from coopdrive.services.sim.truth_series import TruthSeries
from coopdrive.v1 import sim_pb2


def _truth(vid, station_m, speed_mps=10.0, lane=0, accel=0.0, lateral=0.0, automated=True, y_m=None):
    return sim_pb2.VehicleTruth(vehicle_id=vid, x_m=station_m, y_m=3.5 * lane if y_m is None else y_m,
                                station_m=station_m, lane_index=lane, speed_mps=speed_mps, accel_mps2=accel,
                                length_m=4.5, width_m=1.8, lateral_offset_m=lateral, automated=automated)


def test_string_gain_of_a_hand_built_sinusoid_chain_is_exactly_the_amplitude_ratio():
    t = np.arange(0.0, 50.0, 0.01)
    wave = np.sin(2.0 * np.pi * 0.2 * t)
    speeds = [20.0 + amplitude * wave for amplitude in (10.0, 8.0, 6.4)]
    assert string_gain.string_gain(speeds) == pytest.approx(0.8, abs=1e-12)
    assert string_gain.string_gain(speeds, t, frequency_hz=0.2) == pytest.approx(0.8, abs=1e-12)
    assert string_gain.speed_amplitude(speeds[0], t, frequency_hz=0.2) == pytest.approx(10.0, abs=1e-9)


def test_string_gain_with_the_excitation_frequency_is_exact_despite_phase_lags():
    t = np.arange(0.0, 50.0, 0.01)
    speeds = [20.0 + amplitude * np.sin(2.0 * np.pi * 0.2 * t - lag)
              for amplitude, lag in ((10.0, 0.0), (8.0, 0.4), (6.4, 0.8))]
    assert string_gain.string_gain(speeds, t, frequency_hz=0.2) == pytest.approx(0.8, abs=1e-9)


def test_a_leader_at_a_steady_speed_excites_nothing_and_gives_no_string_gain():
    t = np.arange(0.0, 50.0, 0.01)
    rng = np.random.default_rng(1)
    speeds = [22.2 + 1e-4 * rng.standard_normal(t.size), 22.2 + 0.01 * np.sin(2.0 * np.pi * 0.2 * t)]
    assert math.isnan(string_gain.string_gain(speeds, t, frequency_hz=0.2))


def test_string_gain_ignores_a_linear_speed_trend_and_reports_the_worst_pair():
    t = np.arange(0.0, 50.0, 0.01)
    wave = np.sin(2.0 * np.pi * 0.2 * t)
    speeds = [15.0 + 0.1 * t + amplitude * wave for amplitude in (2.0, 1.6, 1.76)]
    assert string_gain.string_gain(speeds, t, frequency_hz=0.2) == pytest.approx(1.1, abs=1e-9)


def test_overlapping_rectangles_count_as_one_collision_while_they_stay_in_contact():
    frames = [(k * 0.1, [_truth("a", 10.0), _truth("b", s)]) for k, s in enumerate([20.0, 14.0, 13.0, 14.5, 30.0])]
    truth = TruthSeries.from_frames(frames)
    assert metrics.collisions(truth) == 1
    result = metrics.gaps(truth)
    assert result["min_gap_m"] == pytest.approx(13.0 - 0.9 - (10.0 + 3.6))


def test_vehicles_side_by_side_in_different_lanes_do_not_collide_but_violate_the_safety_circle():
    truth = TruthSeries.from_frames([(0.0, [_truth("a", 10.0, lane=0), _truth("b", 10.0, lane=1)])])
    assert metrics.collisions(truth) == 0
    assert metrics.safety_circle_violations(truth) == 1
    assert metrics.safety_circle_violations(truth, radius_m=3.0) == 0


def test_min_time_gap_spacing_and_lateral_errors_follow_their_definitions():
    frames = [(k * 0.1, [_truth("lead", 40.0 + k, 20.0), _truth("f", 40.0 + k - 30.0, 20.0, lateral=0.1 * (k % 2))])
              for k in range(10)]
    truth = TruthSeries.from_frames(frames)
    gap = 30.0 - 0.9 - 3.6
    result = metrics.judge(truth, platoon=["lead", "f"], automated=["f"], standstill_m=6.0, headway_s=1.0)
    assert result["min_time_gap_s"] == pytest.approx(gap / 20.0)
    assert result["spacing_error_m"] == pytest.approx(abs(gap - 26.0))  # mean absolute
    assert result["spacing_error_bias_m"] == pytest.approx(gap - 26.0)  # signed mean
    assert result["spacing_error_sd_m"] == pytest.approx(0.0, abs=1e-9)
    assert result["lateral_error_m"] == pytest.approx(0.05)
    assert result["lateral_error_sd_m"] == pytest.approx(0.05)
    assert result["lateral_error_max_m"] == pytest.approx(0.1)


def test_speed_error_is_reported_in_kmh_and_comfort_from_the_acceleration_series():
    frames = [(k * 0.5, [_truth("f", 10.0 * k, 11.0, accel=(-1.0) ** k)]) for k in range(5)]
    truth = TruthSeries.from_frames(frames)
    result = metrics.judge(truth, reference_speed_mps={"f": lambda t: np.full_like(t, 10.0)})
    assert result["speed_error_kmh"] == pytest.approx(3.6)
    assert result["max_abs_accel_mps2"] == 1.0
    assert result["rms_jerk_mps3"] == pytest.approx(4.0)


def test_position_rmse_interpolates_the_truth_at_the_estimate_times():
    true_t = np.array([0.0, 1.0, 2.0])
    true_xy = np.array([[0.0, 0.0], [10.0, 0.0], [20.0, 0.0]])
    rmse = metrics.position_rmse_m(np.array([0.5, 1.5]), np.array([[5.0, 3.0], [19.0, 0.0]]), true_t, true_xy)
    assert rmse == pytest.approx(math.sqrt((9.0 + 16.0) / 2.0))


def test_identity_switches_count_changes_of_a_vehicles_track_id():
    frames = [{"a": 1, "b": 2}, {"a": 1, "b": 3}, {"a": 1}, {"a": 4, "b": 3}]
    assert metrics.identity_switches(frames) == 2


def test_the_judge_reports_the_localisation_rmse_of_the_given_estimates():
    frames = [(k * 1.0, [_truth("f", 10.0 * k)]) for k in range(3)]
    estimates = {"f": (np.array([0.5, 1.5]), np.array([[5.0, 3.0], [15.0, -4.0]]))}
    result = metrics.judge(TruthSeries.from_frames(frames), position_estimates=estimates)
    assert result["position_rmse_m"] == pytest.approx(math.sqrt((9.0 + 16.0) / 2.0))


def test_cars_in_lane_0_of_opposite_roads_do_not_follow_one_another():
    east = _truth("east", 50.0)
    west = sim_pb2.VehicleTruth(vehicle_id="west", x_m=-50.0, y_m=3.5, station_m=60.0, lane_index=0,
                                heading_rad=math.pi, length_m=4.5, width_m=1.8)
    behind_east = _truth("behind", 20.0)
    assert [(a.vehicle_id, b.vehicle_id) for a, b in metrics.following_pairs([east, west, behind_east])] == [
        ("east", "behind")]


def test_cars_in_lane_0_of_a_road_and_of_the_road_before_it_do_not_follow_one_another():
    # A SUMO network's approach to a junction and the edge past it: each measures its stations from its own start.
    past = _truth("past", 20.0)
    past.road_id = "motorway"
    approaching = _truth("approaching", 300.0)
    approaching.road_id = "approach"
    behind_past = _truth("behind", 5.0)
    behind_past.road_id = "motorway"
    assert [(a.vehicle_id, b.vehicle_id) for a, b in metrics.following_pairs([past, approaching, behind_past])] == [
        ("past", "behind")]


def test_a_vehicle_passing_beside_another_in_the_corridor_is_not_following_it():
    # The ambulance is matched to lane 0 but drives 2 m left of the car that moved aside (widths 1.8 m).
    moved_aside = _truth("car", 50.0, lateral=-1.0)
    ambulance = _truth("ambulance", 48.0, lateral=1.0)
    behind = _truth("behind", 30.0, lateral=-1.0)
    pairs = [(a.vehicle_id, b.vehicle_id) for a, b in metrics.following_pairs([moved_aside, ambulance, behind])]
    assert pairs == [("car", "behind")]
    assert metrics.gaps(TruthSeries.from_frames([(0.0, [moved_aside, ambulance, behind])]))["min_gap_m"] == 15.5


def test_the_judge_measures_the_string_gain_only_inside_its_window():
    """Followers damp the 0.2 Hz wave from 10 s to 40 s; after 40 s (a brake, a fault) the follower swings more."""
    frames = []
    for k in range(6000):
        t = k * 0.01
        wave = math.sin(2.0 * math.pi * 0.2 * (t - 10.0)) if t >= 10.0 else 0.0
        follower_amplitude = 1.6 if t < 40.0 else 6.0
        speeds = [20.0 + 2.0 * wave, 20.0 + follower_amplitude * wave]
        frames.append((t, [_truth("lead", 100.0 + 20.0 * t, speeds[0]), _truth("f", 60.0 + 20.0 * t, speeds[1])]))
    truth = TruthSeries.from_frames(frames)
    windowed = metrics.judge(truth, platoon=["lead", "f"], string_start_s=10.0, string_end_s=40.0,
                             string_frequency_hz=0.2)
    to_the_end = metrics.judge(truth, platoon=["lead", "f"], string_start_s=10.0, string_frequency_hz=0.2)
    assert windowed["string_gain"] == pytest.approx(0.8, abs=0.01)
    assert to_the_end["string_gain"] > 1.0


def test_a_run_cut_short_inside_the_string_window_has_no_string_gain():
    """Stopped at 20 s of a 10-40 s window, the run saw the wave's onset only: no gain reported, none judged."""
    frames = []
    for k in range(2001):
        t = k * 0.01
        wave = math.sin(2.0 * math.pi * 0.2 * (t - 10.0)) if t >= 10.0 else 0.0
        frames.append((t, [_truth("lead", 100.0 + 20.0 * t, 20.0 + wave),
                           _truth("f", 60.0 + 20.0 * t, 20.0 + 2.0 * wave)]))
    truth = TruthSeries.from_frames(frames)
    judged = dict(platoon=["lead", "f"], string_start_s=10.0, string_frequency_hz=0.2)
    assert "string_gain" not in metrics.judge(truth, string_end_s=40.0, **judged)
    assert metrics.judge(truth, string_end_s=20.0, **judged)["string_gain"] == pytest.approx(2.0, abs=0.05)


@settings(max_examples=300, deadline=None)
@given(dx=st.floats(-12.0, 12.0), dy=st.floats(-6.0, 6.0), heading_a=st.floats(-math.pi, math.pi),
       heading_b=st.floats(-math.pi, math.pi), length_m=st.floats(1.0, 18.0), width_m=st.floats(0.5, 2.6))
def test_the_reach_shortcut_finds_exactly_the_overlaps_the_corners_find(dx, dy, heading_a, heading_b, length_m, width_m):
    a = sim_pb2.VehicleTruth(vehicle_id="a", heading_rad=heading_a, length_m=4.5, width_m=1.8)
    b = sim_pb2.VehicleTruth(vehicle_id="b", x_m=dx, y_m=dy, heading_rad=heading_b, length_m=length_m, width_m=width_m)
    assert metrics._footprints_overlap(a, b) == geometry.rectangles_overlap(metrics._corners(a), metrics._corners(b))


def _brake_frames(follower_accels, leader_accel=0.0, leader_speed_mps=10.0, leader_station_m=60.0):
    """A follower at 10 m/s 50 m behind a car (or alone, leader_station_m None), one frame per follower
    acceleration."""
    return TruthSeries.from_frames(
        [(0.1 * k, [_truth("f", 10.0, accel=accel)]
          + ([] if leader_station_m is None else
             [_truth("lead", leader_station_m, speed_mps=leader_speed_mps, accel=leader_accel, automated=False)]))
         for k, accel in enumerate(follower_accels)])


def test_a_hard_brake_with_nothing_ahead_braking_or_closing_is_a_phantom_and_lasting_counts_once():
    truth = _brake_frames([0.0, -4.0, -5.0, -3.5, 0.0, -3.2, -1.0])
    assert metrics.hard_brakes(truth, ["f"]) == {"hard_brakes": 2.0, "phantom_brakes": 2.0}
    alone = _brake_frames([0.0, -4.0], leader_station_m=None)
    assert metrics.hard_brakes(alone, ["f"]) == {"hard_brakes": 1.0, "phantom_brakes": 1.0}


def test_a_hard_brake_behind_a_car_braking_beyond_comfort_or_closing_fast_is_called_for():
    behind_braking_car = _brake_frames([0.0, -4.0], leader_accel=-2.5)
    closing = _brake_frames([0.0, -4.0], leader_speed_mps=0.0, leader_station_m=40.0)
    for truth in (behind_braking_car, closing):
        assert metrics.hard_brakes(truth, ["f"]) == {"hard_brakes": 1.0, "phantom_brakes": 0.0}


def test_comfort_braking_and_vehicles_not_judged_count_no_hard_brake():
    truth = _brake_frames([0.0, -2.9, -2.0], leader_accel=-6.0)
    assert metrics.hard_brakes(truth, ["f"]) == {"hard_brakes": 0.0, "phantom_brakes": 0.0}
    assert metrics.hard_brakes(_brake_frames([0.0, -4.0]), ["lead"])["hard_brakes"] == 0.0


def test_the_judge_reports_hard_and_phantom_brakes_of_the_automated_vehicles():
    result = metrics.judge(_brake_frames([0.0, -4.0, 0.0]))
    assert (result["hard_brakes"], result["phantom_brakes"]) == (1.0, 1.0)


def _with_other(other):
    return TruthSeries.from_frames([(0.0, [_truth("f", 10.0), other]), (0.1, [_truth("f", 10.0, accel=-4.0), other])])


def test_a_slower_car_ahead_cutting_in_or_in_the_next_lane_calls_for_the_brake_one_two_lanes_over_does_not():
    for y_m, phantoms in ((2.0, 0.0), (3.5, 0.0), (7.0, 1.0)):
        other = _truth("c", 30.0, speed_mps=5.0, lane=round(y_m / 3.5), y_m=y_m, automated=False)
        assert metrics.hard_brakes(_with_other(other), ["f"])["phantom_brakes"] == phantoms


def test_a_car_crossing_our_path_ahead_calls_for_the_brake():
    crossing = sim_pb2.VehicleTruth(vehicle_id="x", x_m=30.0, y_m=-3.0, heading_rad=math.pi / 2, speed_mps=8.0,
                                    length_m=4.5, width_m=1.8)
    assert metrics.hard_brakes(_with_other(crossing), ["f"]) == {"hard_brakes": 1.0, "phantom_brakes": 0.0}


def test_oncoming_traffic_in_the_next_lane_calls_for_no_brake_oncoming_traffic_in_our_path_does():
    def oncoming(y_m):
        return sim_pb2.VehicleTruth(vehicle_id="o", x_m=40.0, y_m=y_m, heading_rad=math.pi, speed_mps=12.0,
                                    length_m=4.5, width_m=1.8, lane_index=0)
    assert metrics.hard_brakes(_with_other(oncoming(3.5)), ["f"])["phantom_brakes"] == 1.0
    assert metrics.hard_brakes(_with_other(oncoming(0.5)), ["f"])["phantom_brakes"] == 0.0


def test_what_called_for_a_brake_counts_for_as_long_as_a_brake_takes_to_build_up_before_its_onset():
    gone_by = _truth("c", 30.0, speed_mps=5.0, y_m=2.0, automated=False)

    def frames(brake_after_s):
        steps = round(brake_after_s / 0.1)
        return TruthSeries.from_frames([(0.0, [_truth("f", 10.0), gone_by])]
                                       + [(0.1 * k, [_truth("f", 10.0)]) for k in range(1, steps)]
                                       + [(0.1 * steps, [_truth("f", 10.0, accel=-4.0)])])
    assert metrics.hard_brakes(frames(0.8), ["f"])["phantom_brakes"] == 0.0
    assert metrics.hard_brakes(frames(1.5), ["f"])["phantom_brakes"] == 1.0
