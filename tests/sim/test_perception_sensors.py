import math

import numpy as np
import pytest

from coopdrive.services.sim import geometry
from coopdrive.services.sim.camera_sensor import CameraSensor
from coopdrive.services.sim.can_state_sensor import CanStateSensor, DriverPedals, wheel_speeds_mps
from coopdrive.services.sim.lidar_sensor import LidarSensor
from coopdrive.services.sim.profiles import PASSENGER_CAR, TRUCK
from coopdrive.services.sim.radar_sensor import RadarSensor
from coopdrive.services.sim.road_geometry import straight_road
from coopdrive.services.sim.sensor_config import (CameraConfig, CanStateConfig, LidarConfig, RadarConfig,
                                                  SensorTimingConfig, SonarConfig)
from coopdrive.services.sim.sensor_timing import sensor_rng
from coopdrive.services.sim.sonar_sensor import SonarSensor
from coopdrive.services.sim.world_view import WorldView
from coopdrive.v1 import sensors_pb2, sim_pb2
from coopdrive.services.sim.world_profile import ideal

TIMING = SensorTimingConfig(rate_hz=10.0)


def _car(vehicle_id, x_m, y_m=0.0, speed_mps=20.0, heading_rad=0.0, length_m=4.5):
    return sim_pb2.VehicleTruth(vehicle_id=vehicle_id, x_m=x_m, y_m=y_m, heading_rad=heading_rad,
                                speed_mps=speed_mps, length_m=length_m, width_m=1.8)


def _world(*others, ego=None):
    return WorldView(ego=ego or _car("ego", 0.0), others=list(others))


def _rear_gap(other_x_m, other_length_m=4.5):
    """Distance from the ego rear axle to the rear bumper of a vehicle ahead located at its rear axle."""
    return other_x_m - 0.2 * other_length_m


def test_wheel_speeds_follow_speed_yaw_rate_and_track_width():
    fl, fr, rl, rr = wheel_speeds_mps(10.0, 0.2, 2.7, 1.6)
    assert rl == pytest.approx(10.0 - 0.2 * 0.8) and rr == pytest.approx(10.0 + 0.2 * 0.8)
    assert fl == pytest.approx(math.hypot(10.0 - 0.16, 0.2 * 2.7))
    assert fr > fl


def test_can_state_noise_matches_the_configured_sigma():
    config = CanStateConfig(timing=TIMING, wheel_speed_sigma_mps=0.1, yaw_rate_sigma_radps=0.01)
    sensor = CanStateSensor(config, sensor_rng(1, "ego", "can"), PASSENGER_CAR, "ego")
    ego = _car("ego", 0.0, speed_mps=15.0)
    states = [m for k in range(4000) for m in sensor.poll(k * 0.1, ego, 12.0, DriverPedals(throttle_ratio=0.2))]
    wheels = np.array([m.wheel_speed_rear_left_mps for m in states])
    yaw = np.array([m.yaw_rate_radps for m in states])
    assert wheels.mean() == pytest.approx(15.0, abs=0.01)
    assert wheels.std() == pytest.approx(0.1, rel=0.05)
    assert yaw.std() == pytest.approx(0.01, rel=0.05)
    assert states[-1].throttle_pedal_ratio == 0.2 and states[-1].brake_pressure_bar == 12.0
    assert states[-1].header.sequence == 4000


def test_radar_range_noise_matches_config_and_tracks_stay_in_the_narrow_field_of_view():
    config = ideal(RadarConfig(timing=TIMING, range_sigma_m=0.5, range_rate_sigma_mps=0.2))
    sensor = RadarSensor(config, sensor_rng(2, "ego", "radar"), "ego")
    world = _world(_car("lead", 40.0, speed_mps=18.0), _car("side", 20.0, y_m=-15.0), _car("behind", -30.0))
    ranges, rates = [], []
    for k in range(1500):
        for message in sensor.poll(k * 0.1, world):
            assert [t.track_id for t in message.tracks] == [1]
            ranges.append(message.tracks[0].range_m)
            rates.append(message.tracks[0].range_rate_mps)
    assert np.mean(ranges) == pytest.approx(_rear_gap(40.0), abs=0.03)
    assert np.std(ranges) == pytest.approx(0.5, rel=0.08)
    assert np.mean(rates) == pytest.approx(-2.0, abs=0.02)
    assert np.std(rates) == pytest.approx(0.2, rel=0.08)


def test_radar_reports_at_most_the_configured_number_of_tracks_nearest_first():
    config = ideal(RadarConfig(timing=TIMING, max_tracks=3, range_sigma_m=0.0))
    sensor = RadarSensor(config, sensor_rng(2, "e", "r"), "e")
    world = _world(*[_car(f"v{k}", 20.0 + 10.0 * k) for k in range(6)])
    tracks = sensor.poll(0.0, world)[0].tracks
    assert len(tracks) == 3
    assert [round(t.range_m, 3) for t in tracks] == [round(_rear_gap(20.0 + 10.0 * k), 3) for k in range(3)]


def test_lidar_sees_the_nearest_vehicle_and_not_the_one_it_hides():
    config = ideal(LidarConfig(timing=TIMING, range_sigma_m=0.0, layer_elevations_rad=[0.0]))
    sensor = LidarSensor(config, sensor_rng(3, "ego", "lidar"), "ego")
    scan = sensor.poll(0.0, _world(_car("near", 20.0), _car("hidden", 40.0)))[0]
    layer = scan.layers[0]
    azimuths, ranges = np.array(layer.azimuth_rad), np.array(layer.range_m)
    ahead = np.abs(azimuths) < math.radians(0.5)
    assert ranges[ahead] == pytest.approx(_rear_gap(20.0), abs=0.01)
    assert ranges.max() < 25.0
    # Eq. (1): about w / (d tan phi) beams hit the back of a vehicle of width w.
    mount_x_m = sensor.config.mount_x_m
    expected_points = 1.8 / ((_rear_gap(20.0) - mount_x_m) * math.tan(config.azimuth_resolution_rad))
    assert abs(len(ranges) - expected_points) <= 2


def test_lidar_lower_layers_return_from_the_ground_and_range_noise_matches_config():
    config = ideal(LidarConfig(timing=TIMING, range_sigma_m=0.1, layer_elevations_rad=[math.radians(-2.0), 0.0]))
    sensor = LidarSensor(config, sensor_rng(3, "ego", "lidar"), "ego")
    scan = sensor.poll(0.0, _world(_car("lead", 30.0)))[0]
    ground_m = config.mount_height_m / math.tan(math.radians(2.0))
    assert len(scan.layers[0].range_m) == len(sensor.beam_azimuths_rad)
    horizontal = np.array(scan.layers[1].range_m) - _rear_gap(30.0)
    assert np.abs(horizontal).max() < 0.5 and ground_m < 30.0
    samples = []
    for k in range(1, 200):
        samples.extend(np.array(sensor.poll(k * 0.1, _world(_car("lead", 30.0)))[0].layers[1].range_m))
    assert np.std(samples) == pytest.approx(0.1, rel=0.15)


@pytest.mark.parametrize("rear_gap_m, range_sigma_m", [(45.0, 2.25), (10.0, 0.11)])
def test_the_camera_s_range_errs_5_percent_at_45_m_growing_with_its_square_and_its_bearing_a_third_of_a_degree(
        rear_gap_m, range_sigma_m):
    config = CameraConfig(timing=TIMING, miss_probability=0.0, misclassification_probability=0.0).placed()
    sensor = CameraSensor(config, sensor_rng(5, "ego", "camera"), "ego")
    lead_x_m = rear_gap_m + config.mount_x_m + 0.2 * 4.5
    ranges_m, bearings_rad = [], []
    for k in range(400):
        (detection,) = sensor.poll(0.1 * k, _world(_car("lead", lead_x_m)))[0].detections
        x_m, y_m = detection.x_m - config.mount_x_m, detection.y_m
        ranges_m.append(math.hypot(x_m, y_m))
        bearings_rad.append(math.atan2(y_m, x_m))
    assert np.mean(ranges_m) == pytest.approx(rear_gap_m, abs=3.0 * range_sigma_m / math.sqrt(400))
    assert np.std(ranges_m) == pytest.approx(range_sigma_m, rel=0.15)
    assert np.std(bearings_rad) == pytest.approx(math.radians(0.3), rel=0.15)


def test_camera_detects_unoccluded_vehicles_and_fits_the_lane_markings():
    lanes = straight_road(2, width_m=3.5)
    exact = CameraConfig(timing=TIMING, range_sigma_per_m2=0.0, min_range_sigma_m=0.0, bearing_sigma_rad=0.0,
                         lane_offset_sigma_m=0.0, lane_heading_sigma_rad=0.0)
    sensor = CameraSensor(ideal(exact), sensor_rng(4, "ego", "camera"), "ego", lanes)
    ego = _car("ego", 0.0, y_m=0.3)
    frame = sensor.poll(0.0, _world(_car("lead", 25.0), _car("hidden", 45.0), _car("left", 30.0, y_m=3.5),
                                    ego=ego))[0]
    seen = {round(d.x_m) for d in frame.detections}
    assert seen == {round(_rear_gap(25.0)), round(_rear_gap(30.0))}
    assert all(d.object_class == sensors_pb2.OBJECT_CLASS_CAR for d in frame.detections)
    markings = {m.side: m for m in frame.lane_markings}
    assert markings[sensors_pb2.LANE_SIDE_LEFT].c0_m == pytest.approx(1.75 - 0.3, abs=1e-6)
    assert markings[sensors_pb2.LANE_SIDE_RIGHT].c0_m == pytest.approx(-1.75 - 0.3, abs=1e-6)
    assert markings[sensors_pb2.LANE_SIDE_LEFT].c1 == pytest.approx(0.0, abs=1e-9)


def test_sonars_echo_on_a_close_vehicle_and_report_free_space_elsewhere():
    sensor = SonarSensor(SonarConfig(timing=TIMING, range_sigma_m=0.0), sensor_rng(5, "ego", "sonar"), "ego")
    ranges = sensor.poll(0.0, _world(_car("close", 3.6 + 2.0 + 0.9)))[0].ranges
    assert len(ranges) == 6
    assert ranges[1].echo and ranges[1].range_m == pytest.approx(2.0, abs=1e-6)
    assert not ranges[4].echo and ranges[4].range_m == 4.0


def _counting_left_out(monkeypatch, method: str, kept_count) -> list[int]:
    """Wraps Outlines.<method>, a culling of outlines, to record how many each call left out (kept_count(its result):
    how many it kept)."""
    culling = getattr(geometry.Outlines, method)
    left_out = []

    def counting(outlines, *arguments):
        result = culling(outlines, *arguments)
        left_out.append(len(outlines) - kept_count(result))
        return result

    monkeypatch.setattr(geometry.Outlines, method, counting)
    return left_out


def _traffic(seed: int, half_width_m: float, vehicles: int, worlds: int) -> list[WorldView]:
    rng = np.random.default_rng(seed)
    return [_world(*[_car(f"v{k}", *rng.uniform(-half_width_m, half_width_m, 2), heading_rad=rng.uniform(-3.0, 3.0))
                     for k in range(vehicles)]) for _ in range(worlds)]


def _polled(sensor, worlds: list[WorldView]) -> list:
    return [sensor.poll(0.1 * k, world) for k, world in enumerate(worlds)]


def test_sonars_casting_only_at_the_vehicles_near_report_what_casting_at_all_reports(monkeypatch):
    """Traffic around the ego, some of it within the sonars' reach: the same messages, every field."""
    worlds = _traffic(3, 20.0, 6, 30)

    def sonar():
        return SonarSensor(SonarConfig(timing=TIMING), sensor_rng(5, "ego", "sonar"), "ego")

    left_out = _counting_left_out(monkeypatch, "near", len)
    culled = _polled(sonar(), worlds)
    monkeypatch.setattr(geometry.Outlines, "near", lambda outlines, _point, _reach_m: outlines)
    assert culled == _polled(sonar(), worlds)
    assert sum(left_out) > 0
    assert any(reading.echo for polled in culled for message in polled for reading in message.ranges)


def test_a_forward_lidar_casting_only_at_the_vehicles_reaching_ahead_of_it_reports_what_casting_at_all_reports(
        monkeypatch):
    worlds = _traffic(4, 30.0, 8, 10)

    def lidar():
        return LidarSensor(LidarConfig(timing=TIMING), sensor_rng(5, "ego", "lidar"), "ego")

    left_out = _counting_left_out(monkeypatch, "ahead_of", lambda ahead: int(ahead.sum()))
    culled = _polled(lidar(), worlds)
    monkeypatch.setattr(geometry.Outlines, "ahead_of", lambda outlines, _x_m: np.ones(len(outlines), dtype=bool))
    assert culled == _polled(lidar(), worlds)
    assert sum(left_out) > 0


def test_a_sensor_in_forced_dropout_delivers_nothing():
    sensor = SonarSensor(SonarConfig(timing=TIMING), sensor_rng(5, "ego", "sonar"), "ego")
    sensor.set_dropout(True)
    assert sensor.poll(1.0, _world()) == []


def test_mounts_left_out_are_placed_on_the_vehicles_bumpers():
    truck_front_m = TRUCK.length_m - TRUCK.rear_overhang_m
    sonar = SonarSensor(SonarConfig(timing=TIMING, range_sigma_m=0.0), sensor_rng(5, "t", "sonar"), "t", TRUCK)
    ranges = sonar.poll(0.0, _world(_car("close", truck_front_m + 1.5 + 0.9)))[0].ranges
    assert ranges[1].mount_x_m == truck_front_m and ranges[4].mount_x_m == -TRUCK.rear_overhang_m
    assert ranges[1].range_m == pytest.approx(1.5, abs=1e-6)
    radar = RadarSensor(ideal(RadarConfig(timing=TIMING)), sensor_rng(2, "t", "radar"), "t", TRUCK)
    assert radar.config.mount_x_m == truck_front_m
    placed = ideal(RadarConfig(timing=TIMING, mount_x_m=1.0)).placed(TRUCK)
    assert placed.mount_x_m == 1.0
