import numpy as np

from coopdrive.services.scene.occupancy import inside_bodies

REAR_M = np.array([[10.0, 0.0]])
EAST_MPS = np.array([[11.0, 0.0]])
LENGTH_M, WIDTH_M = np.array([4.5]), np.array([1.8])


SENSOR_M = np.zeros(2)


def inside(points, velocity_mps=EAST_MPS, length_m=LENGTH_M, width_m=WIDTH_M, sensor_m=SENSOR_M):
    return inside_bodies(np.array(points, dtype=float), REAR_M, velocity_mps, length_m, width_m, sensor_m).tolist()


def test_a_point_between_the_rear_bumper_and_the_front_within_half_the_width_is_inside():
    assert inside([[10.0, 0.0], [12.0, 0.8], [14.5, -0.9]]) == [True, True, True]


def test_points_behind_the_rear_beyond_the_front_or_beside_the_car_are_outside():
    assert inside([[9.9, 0.0], [14.6, 0.0], [12.0, 1.0], [12.0, -3.5]]) == [False, False, False, False]


def test_the_body_turns_with_the_velocity():
    north = np.array([[0.0, 11.0]])
    assert inside([[10.0, 2.0], [12.0, 0.0]], velocity_mps=north, sensor_m=np.array([10.0, -20.0])) == [True, False]


def test_a_vehicle_coming_towards_the_sensor_oncoming_or_following_holds_no_point():
    assert inside([[9.0, 0.0], [11.0, 0.0]], velocity_mps=-EAST_MPS) == [False, False]
    assert inside([[12.0, 0.0]], sensor_m=np.array([30.0, 0.0])) == [False]


def test_a_car_of_unknown_size_or_too_slow_to_give_a_heading_holds_no_point():
    assert inside([[12.0, 0.0]], length_m=np.array([np.nan])) == [False]
    assert inside([[12.0, 0.0]], width_m=np.array([np.nan])) == [False]
    assert inside([[12.0, 0.0]], velocity_mps=np.array([[0.3, 0.0]])) == [False]


def test_with_no_car_nothing_is_inside():
    assert inside_bodies(np.array([[1.0, 2.0]]), np.zeros((0, 2)), np.zeros((0, 2)), np.zeros(0), np.zeros(0),
                         SENSOR_M).tolist() == [False]
