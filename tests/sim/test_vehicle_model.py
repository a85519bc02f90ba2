import math

import pytest

from coopdrive.services.sim import profiles
from coopdrive.services.sim.vehicle_model import VehicleModel, VehicleState, lag_alpha
from coopdrive.services.sim.world_profile import ideal

# Exact kinematics: the ideal world's vehicles, without driving resistance.
PASSENGER_CAR, TRUCK = ideal(profiles.PASSENGER_CAR), ideal(profiles.TRUCK)


def _unlimited(profile, **changes):
    base = dict(max_jerk_mps3=1e6, response_dead_time_s=0.0, max_accel_mps2=10.0)
    base.update(changes)
    return profile.model_copy(update=base)


def test_the_acceleration_step_response_follows_the_discrete_lag_formula():
    profile = _unlimited(PASSENGER_CAR, response_time_constant_s=0.5)
    model = VehicleModel(profile, dt_s=0.1, state=VehicleState(speed_mps=10.0), substeps=5)
    alpha = lag_alpha(0.02, 0.5)
    expected = 0.0
    for _ in range(20):
        model.step(2.0, 0.0)
        for _ in range(5):
            expected = alpha * 2.0 + (1.0 - alpha) * expected
        assert model.state.accel_mps2 == pytest.approx(expected, abs=1e-12)


def test_dead_time_holds_the_old_acceleration_for_the_configured_delay():
    profile = _unlimited(PASSENGER_CAR, response_dead_time_s=0.3)
    model = VehicleModel(profile, dt_s=0.1, state=VehicleState(speed_mps=10.0), substeps=10)
    for _ in range(3):
        model.step(2.0, 0.0)
        assert model.state.accel_mps2 == 0.0
    model.step(2.0, 0.0)
    assert model.state.accel_mps2 > 0.0


def test_acceleration_jerk_and_steering_limits_are_respected():
    model = VehicleModel(TRUCK, dt_s=0.05, state=VehicleState(speed_mps=20.0))
    previous = model.state
    for k in range(200):
        accel_request = 5.0 if (k // 50) % 2 == 0 else -9.0
        state = model.step(accel_request, 1.0 if k % 40 < 20 else -1.0)
        assert -TRUCK.max_decel_mps2 - 1e-9 <= state.accel_mps2 <= TRUCK.max_accel_mps2 + 1e-9
        assert abs(state.jerk_mps3) <= TRUCK.max_jerk_mps3 + 1e-6
        assert abs(state.steer_rad) <= TRUCK.max_steer_rad + 1e-12
        assert abs(state.steer_rad - previous.steer_rad) <= TRUCK.max_steer_rate_radps * 0.05 + 1e-9
        previous = state


def test_a_vehicle_braking_to_a_stop_does_not_reverse():
    model = VehicleModel(PASSENGER_CAR, dt_s=0.1, state=VehicleState(speed_mps=2.0))
    for _ in range(100):
        model.step(-6.0, 0.0)
    assert model.state.speed_mps == 0.0
    assert model.state.accel_mps2 == 0.0


def test_constant_steering_drives_a_circle_of_the_bicycle_radius():
    profile = PASSENGER_CAR.model_copy(update=dict(steer_dead_time_s=0.0, steer_time_constant_s=0.0,
                                                   max_steer_rate_radps=100.0))
    model = VehicleModel(profile, dt_s=0.1, state=VehicleState(speed_mps=10.0, steer_rad=0.1))
    for _ in range(50):
        model.step(0.0, 0.1)
    assert model.state.yaw_rate_radps == pytest.approx(10.0 * math.tan(0.1) / profile.wheelbase_m)


def test_command_frame_values_map_to_an_acceleration_request_like_actuations_pedal_map():
    model = VehicleModel(_unlimited(PASSENGER_CAR, response_time_constant_s=0.0), dt_s=0.1,
                         state=VehicleState(speed_mps=10.0))
    assert model.command_to_accel_mps2(0.5, 0.0) == pytest.approx(5.0)
    assert model.command_to_accel_mps2(0.5, 0.25) == pytest.approx(-0.25 * PASSENGER_CAR.max_decel_mps2)
    assert model.command_to_accel_mps2(0.0, 0.25, deceleration_request_mps2=3.0) == -3.0
    model.step_command(0.0, 0.25, 0.0, 0.0)
    assert model.state.accel_mps2 == pytest.approx(-2.0)
    assert model.brake_pressure_bar() == pytest.approx(0.25 * PASSENGER_CAR.max_brake_pressure_bar)


def test_driving_resistance_slows_a_coasting_vehicle_and_is_held_at_start():
    profile = PASSENGER_CAR.model_copy(update=dict(rolling_resistance_mps2=0.1, drag_1pm=0.0004))
    model = VehicleModel(profile, dt_s=0.1, state=VehicleState(speed_mps=20.0))
    model.step(model.actuator_accel_mps2, 0.0)
    assert model.state.speed_mps == pytest.approx(20.0, abs=1e-9)
    for _ in range(50):
        model.step(0.0, 0.0)
    assert model.state.speed_mps < 19.5


def test_two_models_with_the_same_inputs_agree_exactly():
    a = VehicleModel(PASSENGER_CAR, 0.02, VehicleState(speed_mps=5.0))
    b = VehicleModel(PASSENGER_CAR, 0.02, VehicleState(speed_mps=5.0))
    for k in range(100):
        assert a.step(math.sin(k / 7), 0.01) == b.step(math.sin(k / 7), 0.01)


def test_driving_resistance_slows_a_coasting_car_by_rolling_and_drag_and_the_grade_adds_gravity():
    car = profiles.PASSENGER_CAR
    model = VehicleModel(car, dt_s=0.02, state=VehicleState(speed_mps=22.2))
    expected_mps2 = car.rolling_resistance_mps2 + car.drag_1pm * 22.2 ** 2
    # About 0.25 m/s2 at 80 km/h, as the control's feed-forward expects of a car.
    assert 0.2 < expected_mps2 < 0.3
    assert model.resistance_mps2(22.2) == pytest.approx(expected_mps2)
    model.grade_rad = math.radians(2.0)
    assert model.resistance_mps2(22.2) == pytest.approx(expected_mps2 + 9.80665 * math.sin(math.radians(2.0)))
    model.grade_rad = 0.0
    for _ in range(150):
        model.step(0.0, 0.0)
    assert model.state.speed_mps < 22.2 - 0.5
    assert model.state.accel_mps2 == pytest.approx(-model.resistance_mps2(model.state.speed_mps), abs=0.01)


def test_an_ideal_world_vehicle_holds_its_speed_with_no_request():
    model = VehicleModel(PASSENGER_CAR, dt_s=0.02, state=VehicleState(speed_mps=22.2))
    for _ in range(50):
        model.step(0.0, 0.0)
    assert model.state.speed_mps == pytest.approx(22.2)
