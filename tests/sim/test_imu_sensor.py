import numpy as np
import pytest

from coopdrive.services.sim.imu_sensor import ImuSensor
from coopdrive.services.sim.sensor_config import ImuConfig, SensorTimingConfig
from coopdrive.services.sim.sensor_timing import sensor_rng
from coopdrive.v1 import sim_pb2
from coopdrive.services.sim.world_profile import ideal


def test_imu_noise_and_bias_match_the_configuration_and_lateral_acceleration_is_centripetal():
    config = ideal(ImuConfig(timing=SensorTimingConfig(rate_hz=100.0), accel_sigma_mps2=0.1, yaw_rate_sigma_radps=0.01,
                       yaw_rate_bias_radps=0.003))
    sensor = ImuSensor(config, sensor_rng(4, "ego", "imu"), "ego")
    ego = sim_pb2.VehicleTruth(vehicle_id="ego", speed_mps=20.0, accel_mps2=-1.0, yaw_rate_radps=0.05)
    samples = [m for k in range(40) for m in sensor.poll(k * 0.1, ego)]
    assert len(samples) == 391
    longitudinal = np.array([m.accel_longitudinal_mps2 for m in samples])
    lateral = np.array([m.accel_lateral_mps2 for m in samples])
    yaw = np.array([m.yaw_rate_radps for m in samples])
    assert longitudinal.mean() == pytest.approx(-1.0, abs=0.02) and longitudinal.std() == pytest.approx(0.1, rel=0.1)
    assert lateral.mean() == pytest.approx(1.0, abs=0.02)
    assert yaw.mean() == pytest.approx(0.053, abs=0.002) and yaw.std() == pytest.approx(0.01, rel=0.1)
