"""The real world's error sources (the configuration defaults) and the ideal world that switches them off."""
import datetime as dt
import math

import numpy as np
import pytest

from coopdrive.services.sim.cam_noise import CamNoise
from coopdrive.services.sim.camera_sensor import CameraSensor
from coopdrive.services.sim.channel_config import RadioChannelConfig
from coopdrive.services.sim.gnss_sensor import GnssSensor
from coopdrive.services.sim.imu_sensor import ImuSensor
from coopdrive.services.sim.lidar_sensor import LidarSensor
from coopdrive.services.sim.profiles import PASSENGER_CAR
from coopdrive.services.sim.radar_sensor import RadarSensor
from coopdrive.services.sim.scenario_config import ScenarioError, parse_scenario
from coopdrive.services.sim.sensor_config import (CameraConfig, FixModeName, GnssConfig, ImuConfig, LidarConfig,
                                                  RadarConfig, SensorTimingConfig)
from coopdrive.services.sim.sensor_timing import SensorTiming, sensor_rng
from coopdrive.services.sim.world_profile import WorldProfile, ideal
from coopdrive.services.sim.world_view import WorldView
from coopdrive.v1 import gnss_pb2, sensors_pb2, sim_pb2

TIMING = SensorTimingConfig(rate_hz=10.0)
EPOCH = dt.datetime(2016, 5, 28, tzinfo=dt.timezone.utc)


def _truth(vehicle_id, x_m, y_m=0.0, speed_mps=20.0, length_m=4.5, width_m=1.8):
    return sim_pb2.VehicleTruth(vehicle_id=vehicle_id, x_m=x_m, y_m=y_m, speed_mps=speed_mps, length_m=length_m,
                                width_m=width_m)


def _scans(sensor, world, count, period_s=0.1):
    return [out for k in range(count) for out in sensor.poll(k * period_s, world)]


def _scenario(**extra):
    data = {"name": "s", "duration_s": 1, "vehicles": [{"vehicle_id": "ego", "station_id": 1, "lane": 0,
                                                        "station_m": 0, "speed_mps": 10}]}
    return parse_scenario({**data, **extra})


def test_the_real_radar_misses_targets_reports_false_tracks_and_noisy_widths_and_the_ideal_one_does_not():
    world = WorldView(_truth("ego", 0.0), [_truth("lead", 40.0)])
    real = _scans(RadarSensor(RadarConfig(timing=TIMING), sensor_rng(1, "ego", "radar"), "ego"), world, 400)
    lead_tracks = [t for scan in real for t in scan.tracks if abs(t.range_m - 38.4) < 2.0]
    false_tracks = [t for scan in real for t in scan.tracks if abs(t.range_m - 38.4) >= 2.0]
    assert 0.9 * 400 < len(lead_tracks) < 0.99 * 400
    assert 40 < len(false_tracks) < 130
    assert all(t.range_rate_mps == pytest.approx(-20.0 * math.cos(t.azimuth_rad)) for t in false_tracks)
    assert np.std([t.width_m for t in lead_tracks]) > 0.1
    perfect = _scans(RadarSensor(ideal(RadarConfig(timing=TIMING)), sensor_rng(1, "ego", "radar"), "ego"), world, 400)
    assert all(len(scan.tracks) == 1 and scan.tracks[0].width_m == 1.8 and scan.tracks[0].track_id == 1
               for scan in perfect)


def test_radar_track_ids_switch_now_and_then_and_unresolved_neighbours_merge_into_one_track():
    world = WorldView(_truth("ego", 0.0), [_truth("lead", 40.0)])
    config = ideal(RadarConfig(timing=TIMING, track_id_switch_probability=0.05))
    ids = {t.track_id for scan in _scans(RadarSensor(config, sensor_rng(2, "e", "r"), "e"), world, 200)
           for t in scan.tracks}
    assert 3 < len(ids) < 30
    side_by_side = WorldView(_truth("ego", 0.0), [_truth("a", 120.0, 0.0), _truth("b", 120.5, 1.9)])
    merged = ideal(RadarConfig(timing=TIMING, range_resolution_m=1.79, azimuth_resolution_rad=math.radians(1.0)))
    scan = RadarSensor(merged, sensor_rng(2, "e", "r"), "e").poll(0.0, side_by_side)[0]
    assert len(scan.tracks) == 1


def test_the_radar_clutter_fault_raises_the_false_tracks_until_it_ends():
    world = WorldView(_truth("ego", 0.0), [])
    sensor = RadarSensor(ideal(RadarConfig(timing=TIMING)), sensor_rng(3, "e", "r"), "e")
    sensor.set_clutter(5.0)
    cluttered = sum(len(s.tracks) for s in _scans(sensor, world, 100))
    sensor.set_clutter(None)
    after = sum(len(s.tracks) for s in [out for k in range(100, 200) for out in sensor.poll(k * 0.1, world)])
    assert 400 < cluttered < 600 and after == 0


def test_real_lidar_beams_drop_out_and_echo_off_clutter_short_of_their_target():
    world = WorldView(_truth("ego", 0.0), [_truth("lead", 30.0, length_m=4.5)])
    config = LidarConfig(timing=TIMING, range_sigma_m=0.0, layer_elevations_rad=[0.0], clutter_probability=0.05)
    real_scans = _scans(LidarSensor(config, sensor_rng(4, "e", "l"), "e"), world, 20)
    real = [r for s in real_scans for r in s.layers[0].range_m]
    perfect = [r for s in _scans(LidarSensor(ideal(config.model_copy(update={"clutter_probability": 0.0})),
                                             sensor_rng(4, "e", "l"), "e"), world, 20) for r in s.layers[0].range_m]
    rear_m = min(perfect)
    assert perfect and all(r < rear_m + 2.0 for r in perfect)
    on_target = [r for r in real if abs(r - rear_m) < 2.0]
    assert len(on_target) < len(perfect)
    assert any(r < rear_m - 2.0 for r in real)


def test_the_real_camera_misses_misclassifies_and_reports_noisy_widths():
    world = WorldView(_truth("ego", 0.0), [_truth("lead", 30.0)])
    config = CameraConfig(timing=TIMING, misclassification_probability=0.2)
    frames = _scans(CameraSensor(config, sensor_rng(5, "e", "c"), "e"), world, 300)
    detections = [d for f in frames for d in f.detections]
    assert 0.9 * 300 < len(detections) < 300
    classes = [d.object_class for d in detections]
    assert 0.1 < 1 - classes.count(sensors_pb2.OBJECT_CLASS_CAR) / len(classes) < 0.3
    assert np.std([d.width_m for d in detections]) > 0.1


def _gnss(config: GnssConfig, seed=7) -> GnssSensor:
    return GnssSensor(config, sensor_rng(seed, "ego", "gnss"), lambda x, y, z: (x * 1e-5, y * 1e-5, z), EPOCH)


def test_the_gnss_error_is_time_correlated_and_rtk_fixed_degrades_to_float_or_dgps_now_and_then():
    ego = _truth("ego", 0.0, speed_mps=0.0)
    config = GnssConfig(timing=TIMING, fix_mode=FixModeName.DGPS, degradation_rate_per_h=0.0,
                        multipath_rate_per_h=0.0)
    correlated = _gnss(config)
    errors = np.array([o.measured_x_m for k in range(600) for o in correlated.poll(k * 0.1, ego)])
    assert np.corrcoef(errors[:-1], errors[1:])[0, 1] > 0.9
    rtk = GnssConfig(timing=TIMING, degradation_rate_per_h=360.0, multipath_rate_per_h=0.0)
    sensor = _gnss(rtk)
    modes = [o.fix.fix_mode for k in range(6000) for o in sensor.poll(k * 0.1, ego)]
    shares = {mode: modes.count(mode) / len(modes) for mode in set(modes)}
    assert shares[gnss_pb2.FIX_MODE_RTK_FIXED] > 0.2
    assert shares.get(gnss_pb2.FIX_MODE_RTK_FLOAT, 0) > 0.05 and shares.get(gnss_pb2.FIX_MODE_DGPS, 0) > 0.02


def test_gnss_multipath_is_frequent_beside_a_truck_and_the_fault_moves_the_fix_while_the_mode_stays():
    ego = _truth("ego", 0.0, speed_mps=0.0)
    truck = _truth("truck", 3.0, 3.5, length_m=12.0)
    config = GnssConfig(timing=TIMING, degradation_rate_per_h=0.0, multipath_rate_per_h=0.0)
    sensor = _gnss(config)
    fixes = [o for k in range(3000) for o in sensor.poll(k * 0.1, ego, [(truck, 3.8)])]
    jumped = [o for o in fixes if o.fix.fix_mode != gnss_pb2.FIX_MODE_NO_FIX and abs(o.measured_x_m) > 0.5]
    outages = [o for o in fixes if o.fix.fix_mode == gnss_pb2.FIX_MODE_NO_FIX]
    assert jumped and outages
    quiet = _gnss(config)
    assert all(abs(o.measured_x_m) < 0.1 for k in range(300) for o in quiet.poll(k * 0.1, ego))
    quiet.set_multipath(3.0, hop_s=1.0)
    moved = [o for k in range(300, 350) for o in quiet.poll(k * 0.1, ego)]
    assert all(1.4 < math.hypot(o.measured_x_m, o.measured_y_m) < 4.6 for o in moved)
    assert all(o.fix.fix_mode == gnss_pb2.FIX_MODE_RTK_FIXED for o in moved)


def test_each_imu_draws_its_own_turn_on_bias_and_the_ideal_one_has_none():
    ego = sim_pb2.VehicleTruth(speed_mps=10.0)
    means = []
    for seed in range(8):
        imu = ImuSensor(ImuConfig(timing=SensorTimingConfig(rate_hz=100.0)), sensor_rng(seed, "e", "imu"), "e")
        samples = [s.accel_longitudinal_mps2 for k in range(400) for s in imu.poll(k * 0.01, ego)]
        means.append(np.mean(samples))
    assert np.std(means) > 0.01
    assert ImuSensor(ideal(ImuConfig()), sensor_rng(1, "e", "imu"), "e").accel_bias_mps2 == 0.0


def test_latency_jitter_delays_samples_but_keeps_them_in_order():
    timing = SensorTiming(SensorTimingConfig(rate_hz=100.0, latency_s=0.005, latency_jitter_s=0.02),
                          np.random.default_rng(1))
    delivered = [d for k in range(500) for _, d, _ in timing.poll(k * 0.01, lambda s: s)]
    assert delivered == sorted(delivered) and len(delivered) > 400
    delays = [d - s for k in range(500, 600) for s, d, _ in timing.poll(k * 0.01, lambda s: s)]
    assert max(delays) > 0.02 and min(delays) >= 0.005


def test_scripted_vehicles_send_what_their_own_receiver_makes_of_their_state():
    noise = CamNoise(GnssConfig(fix_mode=FixModeName.DGPS), np.random.default_rng(1))
    truth = {"x_m": 10.0, "y_m": 5.0, "speed_mps": 20.0, "heading_rad": 0.3, "lane": 0}
    sent = [noise.apply(truth, k * 0.1) for k in range(100)]
    assert 0.05 < np.mean([math.hypot(s["x_m"] - 10.0, s["y_m"] - 5.0) for s in sent]) < 3.0
    assert len({s["speed_mps"] for s in sent}) > 90 and all(s["lane"] == 0 for s in sent)


def test_the_ideal_world_switches_off_what_a_scenario_did_not_set_and_keeps_what_it_did():
    real = _scenario(sensors={"radar": {"miss_probability": 0.2}})
    assert real.world is WorldProfile.REAL and real.channel.burst.good_to_bad_probability > 0
    perfect = _scenario(world="ideal", sensors={"radar": {"miss_probability": 0.2}})
    assert perfect.sensors.radar.miss_probability == 0.2
    assert perfect.sensors.radar.false_alarms_per_scan == 0.0 and perfect.sensors.radar.timing.rate_hz == 20.0
    assert perfect.sensors.gnss.error_correlation_time_s == 0.0
    assert perfect.channel.burst.good_to_bad_probability == 0.0 and perfect.channel.distance_scale_m == 40.0
    assert real.in_world(WorldProfile.IDEAL).sensors.radar.false_alarms_per_scan == 0.0
    assert ideal(RadioChannelConfig()).burst.mean_loss_probability == 0.0
    assert ideal(PASSENGER_CAR).rolling_resistance_mps2 == 0.0 and PASSENGER_CAR.rolling_resistance_mps2 > 0.1


def test_a_scenario_naming_an_unknown_world_gets_a_one_line_error():
    with pytest.raises(ScenarioError, match=r"^<scenario>: world: .*'real' or 'ideal'"):
        _scenario(world="kind")


def test_the_lidar_clutter_fault_sends_more_beams_short_of_their_target_until_it_ends():
    world = WorldView(_truth("ego", 0.0), [_truth("lead", 30.0, length_m=4.5)])
    config = ideal(LidarConfig(timing=TIMING, layer_elevations_rad=[0.0]))
    sensor = LidarSensor(config, sensor_rng(5, "e", "l"), "e")

    def short_returns(first_scan: int) -> int:
        scans = [out for k in range(first_scan, first_scan + 50) for out in sensor.poll(k * 0.1, world)]
        return sum(1 for scan in scans for r in scan.layers[0].range_m if r < 28.0)

    sensor.set_clutter(0.05)
    sprayed = short_returns(0)
    sensor.set_clutter(None)
    assert sprayed > 20 and short_returns(50) == 0
