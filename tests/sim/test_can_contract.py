"""The simulated CAN state and radar tracks fit the vehicle DBC (coopdrive.can) and come back unchanged."""
import pytest

from coopdrive.services.sim.can_state_sensor import CanStateSensor
from coopdrive.services.sim.profiles import TRUCK
from coopdrive.services.sim.radar_sensor import RadarSensor
from coopdrive.services.sim.sensor_config import CanStateConfig, RadarConfig, SensorTimingConfig
from coopdrive.services.sim.sensor_timing import sensor_rng
from coopdrive.services.sim.world_view import WorldView
from coopdrive.v1 import sim_pb2
from coopdrive.services.sim.world_profile import ideal

codec_module = pytest.importorskip("coopdrive.can.codec")
TIMING = SensorTimingConfig(rate_hz=10.0)


def _truth(vehicle_id, x_m, y_m=0.0, speed_mps=20.0):
    return sim_pb2.VehicleTruth(vehicle_id=vehicle_id, x_m=x_m, y_m=y_m, speed_mps=speed_mps, yaw_rate_radps=0.05,
                                steering_angle_rad=0.02, length_m=4.5, width_m=1.8)


def test_the_vehicle_can_state_round_trips_through_the_dbc():
    sensor = CanStateSensor(CanStateConfig(timing=TIMING), sensor_rng(1, "ego", "can"), TRUCK, "ego")
    state = sensor.poll(0.0, _truth("ego", 0.0), brake_pressure_bar=4.0)[0]
    encoder, decoder = codec_module.VehicleCanCodec(), codec_module.VehicleCanCodec()
    decoded = [decoder.decode_vehicle_state(frame) for frame in encoder.encode_vehicle_state(state)]
    result = decoded[-1]
    assert result is not None
    assert result.wheel_speed_rear_left_mps == pytest.approx(state.wheel_speed_rear_left_mps, abs=0.02)
    assert result.yaw_rate_radps == pytest.approx(state.yaw_rate_radps, abs=0.001)
    assert result.brake_pressure_bar == pytest.approx(4.0, abs=0.1)


def test_a_full_radar_scan_fits_the_radar_object_list():
    sensor = RadarSensor(ideal(RadarConfig(timing=TIMING, half_fov_rad=0.5)), sensor_rng(2, "ego", "radar"), "ego")
    world = WorldView(_truth("ego", 0.0), [_truth(f"v{k}", 15.0 + 4.0 * k, y_m=(k % 5 - 2) * 3.0)
                                           for k in range(45)])
    tracks = sensor.poll(0.0, world)[0]
    assert len(tracks.tracks) == 40
    encoder, decoder = codec_module.VehicleCanCodec(), codec_module.VehicleCanCodec()
    results = [decoder.decode_radar(frame) for frame in encoder.encode_radar_tracks(tracks)]
    decoded = [r for r in results if r is not None][-1]
    assert len(decoded.tracks) == 40
    assert sorted(t.range_m for t in decoded.tracks) == pytest.approx(sorted(t.range_m for t in tracks.tracks),
                                                                      abs=0.1)
