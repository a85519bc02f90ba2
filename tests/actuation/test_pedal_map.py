import pytest

from coopdrive.services.actuation.config import CAR_PEDAL_PROFILE, TRUCK_PEDAL_PROFILE
from coopdrive.services.actuation.pedal_map import PedalMap


def test_full_throttle_gives_the_drivertive_voltages_of_eqs_1_and_2():
    command = PedalMap(CAR_PEDAL_PROFILE).map(CAR_PEDAL_PROFILE.accel_at_full_throttle_mps2)
    assert command.reference == 1.0
    assert command.throttle_voltage_v == pytest.approx(0.4 + 3.2)
    assert command.throttle_half_voltage_v == pytest.approx(0.2 + 1.6)


def test_a_released_throttle_still_gets_the_offset_voltage():
    command = PedalMap(CAR_PEDAL_PROFILE).map(0.0)
    assert command.throttle_voltage_v == pytest.approx(0.4)
    assert command.throttle_half_voltage_v == pytest.approx(0.2)


def test_full_brake_asks_the_drivertive_pedal_pressure_of_eq_3():
    command = PedalMap(CAR_PEDAL_PROFILE).map(-CAR_PEDAL_PROFILE.decel_at_full_brake_mps2)
    assert command.reference == -1.0
    assert command.brake_pedal_pressure == pytest.approx(300.0)
    assert command.brake_ratio == 1.0


@pytest.mark.parametrize("accel_mps2", [-20.0, -3.0, -0.1, 0.0, 0.1, 1.0, 20.0])
def test_throttle_and_brake_are_never_applied_together(accel_mps2):
    command = PedalMap(CAR_PEDAL_PROFILE).map(accel_mps2)
    assert command.throttle_ratio == 0.0 or command.brake_ratio == 0.0
    assert -1.0 <= command.reference <= 1.0


def test_half_the_full_throttle_acceleration_is_half_throttle():
    command = PedalMap(CAR_PEDAL_PROFILE).map(CAR_PEDAL_PROFILE.accel_at_full_throttle_mps2 / 2.0)
    assert command.throttle_ratio == pytest.approx(0.5)


def test_the_car_does_not_use_a_deceleration_request_but_the_truck_does():
    car = PedalMap(CAR_PEDAL_PROFILE).map(-2.0)
    truck = PedalMap(TRUCK_PEDAL_PROFILE).map(-2.0)
    assert car.deceleration_request_mps2 == 0.0
    assert truck.deceleration_request_mps2 == pytest.approx(2.0)
    assert truck.brake_ratio == pytest.approx(2.0 / TRUCK_PEDAL_PROFILE.decel_at_full_brake_mps2)


def test_the_truck_needs_more_throttle_than_the_car_for_the_same_acceleration():
    assert PedalMap(TRUCK_PEDAL_PROFILE).map(0.5).throttle_ratio > PedalMap(CAR_PEDAL_PROFILE).map(0.5).throttle_ratio
