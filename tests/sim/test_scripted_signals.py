"""Scripted vehicles obey the traffic lights: they stop at the stop line on red (and on amber when they can stop at
a comfortable deceleration), go on green, and drive through an amber they are too close to stop for."""

import pytest

from coopdrive.messages.vehicle_frame import rear_overhang_m
from coopdrive.services.sim.participants import SIGNAL_STOP_DECEL_MPS2, STOP_LINE_MARGIN_M, ScriptedVehicle
from coopdrive.services.sim.profiles import PASSENGER_CAR
from coopdrive.services.sim.road_geometry import straight_road
from coopdrive.services.sim.signal_controller import SignalController
from coopdrive.services.sim.signal_plan import SignalPlan, SignalStage
from coopdrive.services.sim.speed_profiles import ConstantSpeed
from coopdrive.services.sim.stop_line import StopLine

STEP_S = 0.02
SPEED_MPS = 13.9
STOP_STATION_M = 200.0
FRONT_M = PASSENGER_CAR.length_m - rear_overhang_m(PASSENGER_CAR.length_m)
# Group 1 green 20 s, amber 3 s, then red while group 9 has its stage, red-amber 1 s: a 50 s cycle.
PLAN = dict(stages=[SignalStage(groups=[1], green_s=20.0), SignalStage(groups=[9], green_s=20.0)], amber_s=3.0,
            all_red_s=2.0, red_amber_s=1.0)


def drive(offset_s: float, front_distance_m: float, until_s: float):
    """(time, front distance to the stop line, speed, acceleration) each step of a car that starts front_distance_m
    before the stop line at 50 km/h, the cycle starting at offset_s."""
    lane = straight_road(1)[0]
    line = StopLine(1, 1, "road", lane, STOP_STATION_M, 15.0, SignalController(SignalPlan(offset_s=offset_s, **PLAN)))
    car = ScriptedVehicle("car", 7, PASSENGER_CAR, [lane], 0, STOP_STATION_M - front_distance_m - FRONT_M,
                          ConstantSpeed(speed_mps=SPEED_MPS))
    car.stop_lines = [line]
    samples = []
    for k in range(1, round(until_s / STEP_S) + 1):
        truth = car.step(k * STEP_S)
        samples.append((k * STEP_S, STOP_STATION_M - truth.station_m - FRONT_M, truth.speed_mps, truth.accel_mps2))
    return samples


def hardest_brake_mps2(samples):
    """The strongest deceleration while moving (the step that ends a stop takes its last centimetres at once)."""
    return -min(accel for _, _, speed_mps, accel in samples if speed_mps > 2.0 * SIGNAL_STOP_DECEL_MPS2 * STEP_S)


def crossing_s(samples):
    return next(t for t, distance_m, _, _ in samples if distance_m < 0.0)


def test_a_scripted_car_stops_at_the_stop_line_on_red_and_goes_on_green():
    # Red until 24 s (then red-amber to 25 s); the car arrives after some 7 s.
    samples = drive(offset_s=-25.0, front_distance_m=100.0, until_s=40.0)
    waiting = [(distance_m, speed_mps) for t, distance_m, speed_mps, _ in samples if 15.0 < t < 24.0]
    assert all(speed_mps < 0.1 for _, speed_mps in waiting)
    assert all(0.0 <= distance_m <= STOP_LINE_MARGIN_M + 0.5 for distance_m, _ in waiting)
    assert 25.0 <= crossing_s(samples) < 30.0
    assert hardest_brake_mps2(samples) <= SIGNAL_STOP_DECEL_MPS2 + 0.1


def test_a_scripted_car_too_close_to_stop_on_amber_drives_through_before_red():
    # Amber from 3 s to 6 s; 20 m before the line then, it would need 4.8 m/s2 to stop.
    samples = drive(offset_s=-17.0, front_distance_m=20.0 + 3.0 * SPEED_MPS, until_s=10.0)
    assert 3.0 < crossing_s(samples) < 6.0
    assert min(speed_mps for _, _, speed_mps, _ in samples) == pytest.approx(SPEED_MPS)


def test_a_scripted_car_that_can_stop_comfortably_on_amber_stops_and_never_enters_on_red():
    # 60 m before the line at the amber's onset: 32 m would do at 3 m/s2.
    # Red from 6 s to 32 s, red-amber to 33 s.
    samples = drive(offset_s=-17.0, front_distance_m=60.0 + 3.0 * SPEED_MPS, until_s=40.0)
    red = [distance_m for t, distance_m, _, _ in samples if 6.0 <= t < 33.0]
    assert min(red) >= 0.0
    assert hardest_brake_mps2(samples) <= SIGNAL_STOP_DECEL_MPS2 + 0.1
    assert crossing_s(samples) >= 33.0
