import math

import pytest
from actuation_fixtures import STEP_S, engaged_actuator, mode_request, run, vehicle_state

from coopdrive.services.actuation.config import OverrideConfig
from coopdrive.services.actuation.override import DriverOverrideDetector
from coopdrive.v1 import actuation_pb2

STEERING_RATIO = 15.0


def detector(**config) -> DriverOverrideDetector:
    return DriverOverrideDetector(OverrideConfig(**config), STEERING_RATIO)


def road_wheel_rad(steering_wheel_deg: float) -> float:
    return math.radians(steering_wheel_deg / STEERING_RATIO)


def engaged(d, state, now_s, braking=False, lateral=True, commanded=0.0):
    return d.update(state, now_s, longitudinal_engaged=True, lateral_engaged=lateral,
                    commanded_angle_rad=commanded, automation_braking=braking)


def test_a_steering_error_above_5_deg_for_500_ms_is_a_steering_override():
    d = detector()
    state = vehicle_state(steering_angle_rad=road_wheel_rad(6.0))
    results = [engaged(d, state, i * 0.05) for i in range(11)]
    assert all(r is None for r in results[:10])
    assert results[10].reason == actuation_pb2.OVERRIDE_REASON_STEERING
    assert results[10].value == pytest.approx(6.0)


def test_a_steering_error_that_drops_below_5_deg_restarts_the_500_ms():
    d = detector()
    big, small = vehicle_state(steering_angle_rad=road_wheel_rad(6.0)), vehicle_state()
    assert engaged(d, big, 0.0) is None
    assert engaged(d, small, 0.3) is None
    assert engaged(d, big, 0.4) is None
    assert engaged(d, big, 0.8) is None
    assert engaged(d, big, 0.9).reason == actuation_pb2.OVERRIDE_REASON_STEERING


def test_steering_is_not_watched_when_only_longitudinal_control_is_automated():
    d = detector()
    state = vehicle_state(steering_angle_rad=road_wheel_rad(45.0))
    assert all(engaged(d, state, i * 0.1, lateral=False) is None for i in range(20))


def test_throttle_above_10_percent_is_a_throttle_override():
    d = detector()
    assert engaged(d, vehicle_state(throttle=0.09), 0.0) is None
    assert engaged(d, vehicle_state(throttle=0.11), 0.1).reason == actuation_pb2.OVERRIDE_REASON_THROTTLE


def test_any_brake_pedal_is_a_brake_override_even_while_the_automation_brakes():
    d = detector()
    found = engaged(d, vehicle_state(brake=0.05), 0.0, braking=True)
    assert found.reason == actuation_pb2.OVERRIDE_REASON_BRAKE


def test_brake_pressure_while_the_automation_does_not_brake_is_a_brake_override():
    d = detector()
    found = engaged(d, vehicle_state(brake_pressure_bar=10.0), 0.0, braking=False)
    assert found.reason == actuation_pb2.OVERRIDE_REASON_BRAKE
    assert found.value == 10.0


def test_brake_pressure_just_after_the_automation_released_the_brake_is_given_time_to_fall():
    d = detector(brake_release_grace_s=0.3)
    assert engaged(d, vehicle_state(brake_pressure_bar=10.0), 0.0, braking=True) is None
    assert engaged(d, vehicle_state(brake_pressure_bar=10.0), 0.2, braking=False) is None
    found = engaged(d, vehicle_state(brake_pressure_bar=10.0), 0.35, braking=False)
    assert found.reason == actuation_pb2.OVERRIDE_REASON_BRAKE


def test_the_thresholds_are_configurable():
    d = detector(throttle_pedal_ratio=0.3)
    assert engaged(d, vehicle_state(throttle=0.2), 0.0) is None


def test_an_override_is_reported_once_and_stays_latched_until_rearmed():
    d = detector()
    assert engaged(d, vehicle_state(throttle=0.5), 0.0) is not None
    assert engaged(d, vehicle_state(throttle=0.5), 0.1) is None
    assert d.latched.reason == actuation_pb2.OVERRIDE_REASON_THROTTLE
    d.rearm()
    assert engaged(d, vehicle_state(throttle=0.5), 0.2) is not None


def test_an_override_returns_the_actuator_to_manual_and_it_stays_manual():
    actuator = engaged_actuator()
    run(actuator, 0.0, 0.2)
    detection = actuator.on_vehicle_state(vehicle_state(10.0, throttle=0.5), 0.21)
    assert detection.reason == actuation_pb2.OVERRIDE_REASON_THROTTLE
    frames, status = actuator.step(0.21)
    assert status.mode == actuation_pb2.DRIVING_MODE_MANUAL
    assert "THROTTLE" in status.last_mode_change_reason
    assert actuator.last_command.automation_active is False
    history = run(actuator, 0.21, 1.0)
    assert all(s.mode == actuation_pb2.DRIVING_MODE_MANUAL for _, s in history)
    assert [e.reason for e in actuator.take_override_events()] == [actuation_pb2.OVERRIDE_REASON_THROTTLE]


def test_the_driver_reengages_by_asking_and_not_while_pressing_a_pedal():
    actuator = engaged_actuator()
    actuator.on_vehicle_state(vehicle_state(0.0, brake=0.3), 0.01)
    refused = actuator.on_mode_request(mode_request(actuation_pb2.DRIVING_MODE_AUTONOMOUS), 0.01)
    assert not refused.accepted
    assert "driver not pressing a pedal" in str(refused.unmet)
    run(actuator, 0.01, 0.05, speed_mps=0.0)
    actuator.on_control_command(actuator.watchdog.last_valid_command, 0.05)
    accepted = actuator.on_mode_request(mode_request(actuation_pb2.DRIVING_MODE_AUTONOMOUS), 0.05)
    assert accepted.accepted
    assert actuator.overrides.latched is None


def test_a_driver_steering_against_the_automation_disengages_it():
    actuator = engaged_actuator()
    for i in range(1, 80):
        now_s = i * STEP_S
        actuator.on_vehicle_state(vehicle_state(5.0, steering_angle_rad=road_wheel_rad(20.0)), now_s)
        actuator.on_control_command(actuator.watchdog.last_valid_command, now_s)
        actuator.step(now_s)
    assert actuator.mode == actuation_pb2.DRIVING_MODE_MANUAL
    assert "STEERING" in actuator.modes.last_change_reason


def test_the_driver_can_override_an_emergency_stop_started_after_an_earlier_override():
    actuator = engaged_actuator()
    actuator.on_vehicle_state(vehicle_state(0.0, throttle=0.5), 0.01)
    assert actuator.mode == actuation_pb2.DRIVING_MODE_MANUAL
    actuator.on_estop(0.02)
    assert actuator.mode == actuation_pb2.DRIVING_MODE_SAFE_STOP
    assert actuator.on_vehicle_state(vehicle_state(0.0, throttle=0.5), 0.03) is not None
    assert actuator.mode == actuation_pb2.DRIVING_MODE_MANUAL


def test_an_actuator_lagging_a_brisk_steering_ramp_is_not_the_driver():
    # The automation turns the wheels at 0.4 rad/s (6 deg/s at the steering wheel x 15); the actuator is 0.2 s
    # behind, 80 deg at the wheel off the latest command, but never off the commands of the last 0.35 s.
    d = detector()
    for k in range(100):
        now_s = k * 0.01
        commanded = 0.4 * now_s
        measured = max(0.0, 0.4 * (now_s - 0.2))
        assert engaged(d, vehicle_state(steering_angle_rad=measured), now_s, commanded=commanded) is None


def test_a_driver_holding_the_wheel_against_a_steering_ramp_is_caught():
    d = detector()
    detections = [engaged(d, vehicle_state(steering_angle_rad=0.0), k * 0.01, commanded=0.4 * k * 0.01)
                  for k in range(120)]
    caught = [k * 0.01 for k, detection in enumerate(detections) if detection is not None]
    assert len(caught) == 1
    assert caught[0] == pytest.approx(0.35 + 0.02 + 0.5, abs=0.03)  # off every recent command from ~0.37 s
