import math

import numpy as np
from coopdrive.services.scene.config import FrontFaceConfig
from coopdrive.services.scene.front_faces import facing_sensor, front_offsets, heading_known

SENSOR_M = np.zeros(2)
CONFIG = FrontFaceConfig()
# A settled track: its velocity known to 0.3 m/s on each axis.
SETTLED_COV = np.diag([0.09, 0.09])


def facing(rear_m, velocity_mps, was=False, cov=SETTLED_COV):
    velocity_mps = np.array([velocity_mps], dtype=float)
    known = heading_known(velocity_mps, np.array([cov]), CONFIG)
    direction = velocity_mps / np.linalg.norm(velocity_mps)
    return bool(facing_sensor(np.array([rear_m], dtype=float), direction, known, SENSOR_M, np.array([was]),
                              CONFIG)[0])


def test_a_car_coming_towards_the_sensor_shows_it_its_front():
    assert facing([40.0, 3.5], [-12.0, 0.0])


def test_a_car_driving_away_shows_its_rear():
    assert not facing([40.0, 0.0], [12.0, 0.0])


def test_a_car_following_behind_us_shows_its_front():
    assert facing([-15.0, 0.0], [12.0, 0.0])


def test_a_car_beside_us_no_longer_shows_its_front():
    assert not facing([0.5, 3.5], [-12.0, 0.0], was=True)


def test_between_the_two_angles_the_last_answer_stands():
    angle_rad = 0.5 * (CONFIG.facing_angle_rad + CONFIG.release_angle_rad)
    rear_m = [10.0 * math.cos(angle_rad), 10.0 * math.sin(angle_rad)]
    assert facing(rear_m, [-12.0, 0.0], was=True)
    assert not facing(rear_m, [-12.0, 0.0], was=False)


def test_a_car_waiting_at_the_junction_keeps_the_face_it_showed_while_moving():
    assert facing([20.0, 3.5], [0.3, 0.1], was=True)
    assert not facing([20.0, 3.5], [-0.3, 0.1], was=False)


def test_a_new_track_whose_heading_is_still_its_prior_s_keeps_the_last_answer():
    assert not facing([40.0, 3.5], [-12.0, 0.0], cov=np.diag([100.0, 100.0]))


def test_the_face_seen_is_the_length_ahead_of_the_rear_along_the_direction():
    offsets = front_offsets(np.array([[-1.0, 0.0], [0.0, 1.0]]), np.array([4.5, math.nan]),
                            np.array([True, True]), default_length_m=4.0)
    np.testing.assert_allclose(offsets, [[-4.5, 0.0], [0.0, 4.0]])


def test_a_car_not_facing_the_sensor_is_seen_at_its_rear():
    offsets = front_offsets(np.array([[1.0, 0.0]]), np.array([4.5]), np.array([False]), default_length_m=4.5)
    assert offsets.tolist() == [[0.0, 0.0]]


def test_a_heading_is_known_only_fast_enough_and_certain_enough():
    velocities = np.array([[-12.0, 0.0], [-1.0, 0.0], [-12.0, 0.0]])
    covs = np.array([SETTLED_COV, SETTLED_COV, np.diag([100.0, 100.0])])
    assert heading_known(velocities, covs, CONFIG).tolist() == [True, False, False]
