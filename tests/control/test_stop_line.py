"""A planner's stop line (give way, road works) stops the car before the line, whatever the spacing policy."""

import pytest

from coopdrive.services.control.inputs import STOP_LINE_MARGIN_M, STOP_LINE_OBJECT_ID, stop_line_target
from coopdrive.services.control.longitudinal import LongitudinalController, Spacing
from coopdrive.services.control.profiles import CAR
from coopdrive.v1 import planner_pb2

DT_S = 0.02


def stop_line_request(distance_m, sample_time_s=0.0, standstill_m=6.0, time_gap_s=1.5):
    request = planner_pb2.BehaviourRequest(desired_speed_mps=11.1, has_stop_line=True,
                                           stop_line_distance_m=distance_m)
    request.header.sample_time_s = sample_time_s
    request.spacing.standstill_m = standstill_m
    request.spacing.time_gap_s = time_gap_s
    return request


def drive_to_stop_line(line_m, speed_mps=11.1, duration_s=25.0, planner_period_s=0.1):
    """Car with a first-order driveline lag; the planner re-measures the distance at 10 Hz."""
    controller = LongitudinalController(CAR)
    position_m, accel_mps2, request = 0.0, 0.0, None
    for step in range(int(duration_s / DT_S)):
        now_s = step * DT_S
        if step % round(planner_period_s / DT_S) == 0:
            request = stop_line_request(line_m - position_m, sample_time_s=now_s)
        target = stop_line_target(request, speed_mps, now_s)
        command = controller.step(now_s, speed_mps, accel_mps2, [target], request.desired_speed_mps,
                                  Spacing(request.spacing.standstill_m, request.spacing.time_gap_s))
        accel_mps2 += (command.accel_request_mps2 - accel_mps2) * DT_S / CAR.engine_lag_s
        speed_mps = max(0.0, speed_mps + accel_mps2 * DT_S)
        position_m += speed_mps * DT_S
    return position_m, speed_mps


def test_no_stop_line_means_no_target():
    assert stop_line_target(planner_pb2.BehaviourRequest(), 10.0, 0.0) is None


def test_the_stop_line_is_a_standing_target_whose_distance_is_brought_up_to_date():
    target = stop_line_target(stop_line_request(50.0, sample_time_s=10.0), ego_speed_mps=10.0, now_s=10.1)
    assert target.object_id == STOP_LINE_OBJECT_ID
    assert target.speed_mps == 0.0 and target.accel_mps2 is None
    assert target.gap_m == pytest.approx(49.0 - STOP_LINE_MARGIN_M)
    assert target.stop_line
    assert target.role == planner_pb2.TARGET_ROLE_YIELD


def test_the_car_stops_short_of_the_line_by_the_margin_whatever_the_spacing_policy():
    target = stop_line_target(stop_line_request(30.0, standstill_m=6.0), 0.0, 0.0)
    assert target.gap_m == pytest.approx(30.0 - STOP_LINE_MARGIN_M)


def test_a_car_at_40_kmh_stops_before_a_line_80_m_ahead_and_close_to_it():
    position_m, speed_mps = drive_to_stop_line(80.0)
    assert speed_mps < 0.1
    assert 80.0 - STOP_LINE_MARGIN_M - 0.5 < position_m < 80.0


def test_a_line_too_close_for_comfort_braking_is_still_not_crossed():
    position_m, speed_mps = drive_to_stop_line(30.0, speed_mps=50 / 3.6, duration_s=20.0)
    assert speed_mps < 0.1 and position_m < 30.0


def test_a_line_already_passed_holds_the_car_at_standstill():
    position_m, speed_mps = drive_to_stop_line(0.0, speed_mps=0.0, duration_s=5.0)
    assert speed_mps == 0.0 and position_m == pytest.approx(0.0, abs=0.05)


def peak_deceleration_mps2(line_m, speed_mps, duration_s=25.0):
    """The largest deceleration the car's driveline gives on the way to a line first seen line_m ahead."""
    controller = LongitudinalController(CAR)
    position_m, accel_mps2, peak_mps2 = 0.0, 0.0, 0.0
    for step in range(int(duration_s / DT_S)):
        now_s = step * DT_S
        request = stop_line_request(line_m - position_m, sample_time_s=now_s)
        command = controller.step(now_s, speed_mps, accel_mps2, [stop_line_target(request, speed_mps, now_s)],
                                  request.desired_speed_mps, Spacing(6.0, 1.5))
        accel_mps2 += (command.accel_request_mps2 - accel_mps2) * DT_S / CAR.engine_lag_s
        speed_mps = max(0.0, speed_mps + accel_mps2 * DT_S)
        position_m += speed_mps * DT_S
        peak_mps2 = max(peak_mps2, -accel_mps2)
    return peak_mps2


def test_a_car_above_the_planned_braking_curve_brakes_on_the_curve_through_its_own_state_not_at_the_comfort_limit():
    """50 km/h, 80 m from the line: the constant deceleration that stops it there is 1.2 m/s2 (eq. SL3); the curve
    of the planned 1 m/s2 alone (SL2) asked the comfort limit, 2 m/s2."""
    speed_mps, stop_m = 50 / 3.6, 80.0 - STOP_LINE_MARGIN_M
    needed_mps2 = speed_mps ** 2 / (2 * stop_m)
    assert needed_mps2 < peak_deceleration_mps2(80.0, speed_mps) < 1.2 * needed_mps2
