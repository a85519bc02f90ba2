import math

import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from coopdrive.services.sim.profiles import PASSENGER_CAR, TRUCK
from coopdrive.services.sim.road_geometry import StraightLane, straight_road
from coopdrive.services.sim.vehicle_model import VehicleModel, VehicleState
from coopdrive.services.sim.vehicle_truth import NO_LANE, vehicle_truth


def test_the_truth_places_the_vehicle_on_the_nearest_lane_of_its_direction():
    lanes = straight_road(2) + [StraightLane(lane_index=0, x0_m=50.0, y0_m=-100.0, heading_rad=math.pi / 2)]
    state = VehicleState(x_m=120.0, y_m=3.2, heading_rad=0.01, speed_mps=11.0, steer_rad=0.002)
    truth = vehicle_truth("ego", 5, state, PASSENGER_CAR, lanes)
    assert (truth.lane_index, truth.station_m, truth.lateral_offset_m) == pytest.approx((1, 120.0, -0.3))
    assert truth.steering_angle_rad == 0.002 and truth.automated and truth.length_m == PASSENGER_CAR.length_m
    crossing = vehicle_truth("x", 6, VehicleState(x_m=50.0, y_m=3.0, heading_rad=-math.pi), PASSENGER_CAR, lanes)
    assert crossing.lane_index == NO_LANE


@settings(max_examples=40, deadline=None)
@given(st.lists(st.tuples(st.floats(-20.0, 20.0), st.floats(-1.0, 1.0)), min_size=1, max_size=30),
       st.sampled_from([PASSENGER_CAR, TRUCK]))
def test_any_request_sequence_keeps_the_vehicle_within_its_limits(requests, profile):
    model = VehicleModel(profile, dt_s=0.05, state=VehicleState(speed_mps=15.0))
    for accel_request, steer_request in requests:
        previous = model.state
        state = model.step(accel_request, steer_request)
        assert -profile.max_decel_mps2 - 1e-9 <= state.accel_mps2 <= profile.max_accel_mps2 + 1e-9
        assert abs(state.steer_rad) <= profile.max_steer_rad + 1e-12
        assert abs(state.steer_rad - previous.steer_rad) <= profile.max_steer_rate_radps * 0.05 + 1e-9
        assert 0.0 <= state.speed_mps <= profile.max_speed_mps
        assert abs(model.actuator_accel_mps2) <= max(profile.max_accel_mps2, profile.max_decel_mps2) + 1e-9
