"""All simulated sensors of one vehicle, built from its configuration and the run seed, polled together."""
from __future__ import annotations

import datetime as dt
from dataclasses import dataclass, field
from typing import Sequence

from coopdrive.services.sim.camera_sensor import CameraSensor
from coopdrive.services.sim.can_state_sensor import CanStateSensor, DriverPedals
from coopdrive.services.sim.fault_config import SensorName
from coopdrive.services.sim.gnss_sensor import GnssOutput, GnssSensor, ToGeodetic
from coopdrive.services.sim.imu_sensor import ImuSensor
from coopdrive.services.sim.lidar_sensor import LidarSensor
from coopdrive.services.sim.profiles import VehicleProfile
from coopdrive.services.sim.radar_sensor import RadarSensor
from coopdrive.services.sim.road_geometry import LaneGeometry
from coopdrive.services.sim.sensor_config import SensorSuiteConfig
from coopdrive.services.sim.sensor_timing import sensor_rng
from coopdrive.services.sim.sonar_sensor import SonarSensor
from coopdrive.services.sim.world_view import WorldView
from coopdrive.v1 import sensors_pb2, vehicle_pb2


@dataclass
class SensorOutputs:
    """What became available at one poll, each list oldest first."""

    gnss: list[GnssOutput] = field(default_factory=list)
    can_state: list[vehicle_pb2.VehicleCanState] = field(default_factory=list)
    imu: list[vehicle_pb2.ImuSample] = field(default_factory=list)
    radar: list[sensors_pb2.RadarTracks] = field(default_factory=list)
    lidar: list[sensors_pb2.LidarScan] = field(default_factory=list)
    camera: list[sensors_pb2.CameraFrame] = field(default_factory=list)
    sonar: list[sensors_pb2.SonarRanges] = field(default_factory=list)


class SensorSuite:
    def __init__(self, config: SensorSuiteConfig, seed: int, vehicle_id: str, profile: VehicleProfile,
                 to_geodetic: ToGeodetic, utc_epoch: dt.datetime, lanes: Sequence[LaneGeometry] = ()) -> None:
        def rng(name: SensorName):
            return sensor_rng(seed, vehicle_id, name.value)

        self.vehicle_id = vehicle_id
        self.gnss = GnssSensor(config.gnss, rng(SensorName.GNSS), to_geodetic, utc_epoch, vehicle_id)
        self.can_state = CanStateSensor(config.can_state, rng(SensorName.CAN_STATE), profile, vehicle_id)
        self.imu = ImuSensor(config.imu, rng(SensorName.IMU), vehicle_id)
        self.radar = RadarSensor(config.radar, rng(SensorName.RADAR), vehicle_id, profile)
        self.lidar = LidarSensor(config.lidar, rng(SensorName.LIDAR), vehicle_id, profile)
        self.camera = CameraSensor(config.camera, rng(SensorName.CAMERA), vehicle_id, lanes, profile)
        self.sonar = SonarSensor(config.sonar, rng(SensorName.SONAR), vehicle_id, profile)
        self._by_name = {SensorName.GNSS: self.gnss, SensorName.CAN_STATE: self.can_state, SensorName.IMU: self.imu,
                         SensorName.RADAR: self.radar, SensorName.LIDAR: self.lidar,
                         SensorName.CAMERA: self.camera, SensorName.SONAR: self.sonar}

    def seen_vehicle_ids(self) -> set[str]:
        """The vehicles this vehicle's camera detected or its radar tracked so far in the run."""
        return self.camera.detected_ids() | self.radar.tracked_ids()

    def set_dropout(self, sensor: SensorName, active: bool) -> None:
        self._by_name[sensor].set_dropout(active)

    def poll(self, now_s: float, world: WorldView, brake_pressure_bar: float,
             driver: DriverPedals = DriverPedals()) -> SensorOutputs:
        """world.ego is this vehicle's truth at now_s; every sensor samples what is due and hands over what
        its latency lets out by now_s."""
        return SensorOutputs(
            gnss=self.gnss.poll(now_s, world.ego, [(o, world.height_m(o)) for o in world.others]),
            can_state=self.can_state.poll(now_s, world.ego, brake_pressure_bar, driver),
            imu=self.imu.poll(now_s, world.ego),
            radar=self.radar.poll(now_s, world),
            lidar=self.lidar.poll(now_s, world),
            camera=self.camera.poll(now_s, world),
            sonar=self.sonar.poll(now_s, world),
        )
