import math

import numpy as np
import pytest

from coopdrive.services.scene.config import LidarConfig
from coopdrive.services.scene.lidar import LidarClusterer, expected_points, max_detection_range_m, split_consecutive
from coopdrive.services.scene.measurement import EgoPose
from coopdrive.v1 import header_pb2, sensors_pb2

from .helpers import lidar_scan


def scan_of_points(points_by_layer: dict[int, list[tuple[float, float]]]) -> sensors_pb2.LidarScan:
    scan = sensors_pb2.LidarScan(max_range_m=100.0)
    for layer_id, points in points_by_layer.items():
        layer = scan.layers.add(layer=layer_id)
        for x, y in points:
            layer.azimuth_rad.append(math.atan2(y, x))
            layer.range_m.append(math.hypot(x, y))
    return scan


def row(x_m: float, y_from_m: float, count: int, step_m: float = 0.2) -> list[tuple[float, float]]:
    return [(x_m, y_from_m + i * step_m) for i in range(count)]


def test_consecutive_points_split_where_the_gap_exceeds_one_metre():
    points = np.array([[10.0, 0.0], [10.0, 0.9], [10.0, 1.8], [10.0, 2.81]])
    runs = split_consecutive(points, 1.0)
    assert [len(r) for r in runs] == [3, 1]


def test_two_cars_1_2_m_apart_become_two_clusters_and_0_8_m_apart_one():
    clusterer = LidarClusterer(LidarConfig())
    apart = scan_of_points({2: row(15.0, -2.0, 8) + row(15.0, -0.6 + 1.2, 8)})
    touching = scan_of_points({2: row(15.0, -2.0, 8) + row(15.0, -0.6 + 0.8, 8)})
    assert len(clusterer.clusters(apart)) == 2
    assert len(clusterer.clusters(touching)) == 1


def test_clusters_with_fewer_than_five_points_are_dropped():
    clusterer = LidarClusterer(LidarConfig())
    scan = scan_of_points({2: row(12.0, -3.0, 4) + row(12.0, 1.0, 5)})
    clusters = clusterer.clusters(scan)
    assert [len(c.points_m) for c in clusters] == [5]


def test_clusters_beyond_the_road_side_or_too_long_are_dropped():
    clusterer = LidarClusterer(LidarConfig())
    guard_rail = [(5.0 + 0.5 * i, -4.0) for i in range(60)]
    off_road = row(20.0, 8.0, 10)
    car = row(20.0, -0.9, 10)
    clusters = clusterer.clusters(scan_of_points({2: guard_rail + off_road + car}))
    assert len(clusters) == 1
    assert clusters[0].rear_centre_m == pytest.approx([20.0, 0.0])


def test_returns_at_or_beyond_max_range_are_not_points_and_widen_the_gap():
    scan = lidar_scan(0.0, [(20.0, 0.0, 1.8)])
    assert len(LidarClusterer(LidarConfig()).clusters(scan)) == 1
    empty = lidar_scan(0.0, [])
    assert LidarClusterer(LidarConfig()).clusters(empty) == []


def test_the_same_car_on_two_layers_is_one_cluster_but_only_chosen_layers_count():
    scan = scan_of_points({2: row(20.0, -0.9, 10), 3: row(20.1, -0.9, 10)})
    assert len(LidarClusterer(LidarConfig()).clusters(scan)) == 1
    only_layer_3 = LidarClusterer(LidarConfig(object_layers=[3])).clusters(scan)
    assert [c.layers for c in only_layer_3] == [(3,)]


def test_a_cluster_becomes_an_enu_measurement_of_the_rear_bumper_centre():
    pose = EgoPose(time_s=1.0, x_m=100.0, y_m=50.0, heading_rad=math.pi / 2, speed_mps=0.0,
                   yaw_rate_radps=0.0, accel_mps2=0.0, position_cov_m2=np.zeros((2, 2)))
    scan = scan_of_points({2: row(20.0, -0.9, 10)})
    (meas,) = LidarClusterer(LidarConfig()).measurements(scan, pose)
    assert meas.source == header_pb2.SENSOR_SOURCE_LIDAR
    assert meas.time_s == 1.0
    assert meas.position_m == pytest.approx([100.0, 70.0])
    assert meas.width_m == pytest.approx(1.8)
    # Heading north: range error lies along y, bearing error along x.
    assert meas.cov_m2[1, 1] == pytest.approx(0.1**2, rel=1e-3)
    assert meas.cov_m2[0, 0] > meas.cov_m2[1, 1]


def test_a_layer_with_mismatched_arrays_is_a_clear_error():
    scan = sensors_pb2.LidarScan()
    layer = scan.layers.add(layer=2)
    layer.azimuth_rad.extend([0.0, 0.1])
    layer.range_m.extend([5.0])
    with pytest.raises(ValueError, match="layer 2"):
        LidarClusterer(LidarConfig()).clusters(scan)


def test_heudiasyc_eq_1_gives_about_ten_points_on_a_2_m_car_at_22_m_with_half_degree_beams():
    assert expected_points(2.0, 22.0, math.radians(0.5)) == pytest.approx(10.4, abs=0.1)
    # With five points required, such a car is detected out to about 46 m.
    assert max_detection_range_m(2.0, 5, math.radians(0.5)) == pytest.approx(45.8, abs=0.1)


def test_the_lower_layers_that_see_the_ground_are_not_used_for_objects_by_default():
    ground_arc = [(23.9 * math.cos(a), 23.9 * math.sin(a)) for a in np.arange(-0.3, 0.3, math.radians(0.5))]
    scan = scan_of_points({0: ground_arc, 2: row(20.0, -0.9, 10)})
    (cluster,) = LidarClusterer(LidarConfig()).clusters(scan)
    assert cluster.layers == (2,)


def test_a_flank_cut_by_the_edge_of_the_field_of_view_only_places_the_vehicle_sideways():
    pose = EgoPose(time_s=1.0, x_m=0.0, y_m=0.0, heading_rad=0.0, speed_mps=10.0,
                   yaw_rate_radps=0.0, accel_mps2=0.0, position_cov_m2=np.zeros((2, 2)))
    config = LidarConfig(half_fov_rad=math.radians(50.0))
    clusterer = LidarClusterer(config, front_bumper_x_m=3.6)
    # A car passing on the left, 2.5 m out: the beam along the 50 degree edge meets its flank 2.1 m ahead
    # of the scanner, and the flank is seen from there forwards.
    edge_x_m = 3.6 + 2.5 / math.tan(math.radians(50.0))
    (cut,) = clusterer.measurements(scan_of_points({2: [(edge_x_m + 0.3 * i, 2.5) for i in range(12)]}), pose)
    assert cut.ambiguous
    assert math.sqrt(cut.cov_m2[0, 0]) >= config.typical_length_m
    assert math.sqrt(cut.cov_m2[1, 1]) < 1.0
    # The same car further ahead, whole inside the field of view, is an ordinary reading.
    (whole,) = clusterer.measurements(scan_of_points({2: [(edge_x_m + 4.0 + 0.3 * i, 2.5) for i in range(12)]}), pose)
    assert not whole.ambiguous
    assert math.sqrt(whole.cov_m2[0, 0]) < 1.0


def test_a_car_beside_us_cut_down_by_the_field_of_view_is_placed_half_a_width_out_from_its_near_side():
    """The edge of the field of view hides the outer part of a car passing on our left: the middle of what is
    left slid a metre towards our lane as the car came beside us, and read as a car turning across our path."""
    pose = EgoPose(time_s=1.0, x_m=0.0, y_m=0.0, heading_rad=0.0, speed_mps=10.0,
                   yaw_rate_radps=0.0, accel_mps2=0.0, position_cov_m2=np.zeros((2, 2)))
    config = LidarConfig(half_fov_rad=math.radians(50.0))
    clusterer = LidarClusterer(config, front_bumper_x_m=3.6)
    near_side_m = 2.6
    edge_x_m = 3.6 + near_side_m / math.tan(math.radians(50.0))
    flank = [(edge_x_m + 0.3 * i, near_side_m) for i in range(12)]
    # The front face as far out as the field of view still shows it, and the flank behind it.
    face = [(edge_x_m, near_side_m + 0.1 * i) for i in range(1, 6)]
    expected_m = near_side_m + 0.5 * config.typical_width_m
    for points in (flank, face + flank):
        (reading,) = clusterer.measurements(scan_of_points({2: points}), pose)
        assert reading.ambiguous
        assert reading.position_m[1] == pytest.approx(expected_m)
    # On our right the same, mirrored.
    (right,) = clusterer.measurements(scan_of_points({2: [(x, -y) for x, y in flank]}), pose)
    assert right.position_m[1] == pytest.approx(-expected_m)
    # A car wholly in view keeps the middle of its face.
    (whole,) = clusterer.measurements(scan_of_points({2: row(edge_x_m + 4.0, near_side_m, 10)}), pose)
    assert whole.position_m[1] == pytest.approx(near_side_m + 0.9)


def test_a_stray_echo_in_front_of_a_car_does_not_cut_it_into_two_clusters():
    face = row(17.7, -0.9, 10)
    echo = [(9.0, face[5][1] * 9.0 / 17.7 - 0.01)]
    scan = scan_of_points({2: face[:5] + echo + face[5:]})
    (cluster,) = LidarClusterer(LidarConfig()).clusters(scan)
    assert len(cluster.points_m) == 10
    assert cluster.rear_centre_m == pytest.approx([17.7, 0.0])
