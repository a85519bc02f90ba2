"""Scene service: wires sensor frames, the ego state and decoded CAMs into SceneFusion."""

from __future__ import annotations

from coopdrive.bus import Envelope
from coopdrive.can.bus_input import VehicleBusInput
from coopdrive.can.bus_reader import VehicleBusReader
from coopdrive.geodesy import LocalTangentPlane
from coopdrive.roadmap import RoadMap
from coopdrive.runtime.service import Service
from coopdrive.services.scene.config import SceneConfig
from coopdrive.services.scene.fusion import SceneFusion
from coopdrive.services.scene.intended_accel import IntendedAccelerations
from coopdrive.services.scene.measurement import V2vObservation
from coopdrive.services.scene.road_lanes import EgoRoadLanes

SENSOR_TOPICS = {"lidar/scan": "on_lidar", "camera/frame": "on_camera", "sonar/ranges": "on_sonar"}


class SceneService(Service):
    name = "scene"
    Config = SceneConfig

    def start(self) -> None:
        config: SceneConfig = self.config
        self.road_map = RoadMap.load(config.map_name) if config.map_name else None
        if self.road_map is not None:
            self.origin = self.road_map.origin
        else:
            self.origin = config.origin.as_tuple()
        self.plane = LocalTangentPlane(*self.origin)
        self.road_lanes = EgoRoadLanes(self.road_map) if self.road_map is not None else None
        self.fusion = SceneFusion(config.fusion, lane_of=self.road_lanes.lane_of if self.road_lanes else None)
        self.ctx.subscribe("ego/state", self.on_ego)
        for topic, method in SENSOR_TOPICS.items():
            self.ctx.subscribe(topic, self._sensor_handler(method))
        self.vehicle_bus = VehicleBusInput(self.ctx, VehicleBusReader(
            on_radar_tracks=self.fusion.on_radar, radar_latency_s=config.radar_latency_s,
            vehicle_can=config.vehicle_can), config.can_port)
        self.ctx.subscribe("v2x/cam", self.on_cam)
        self.ctx.subscribe("v2x/status", self.on_v2x_status)
        self.intended = IntendedAccelerations(config.intended_accel_max_age_s, config.fusion.trust.min_trusted)
        self.ctx.subscribe("v2x/iclcm", lambda envelope: self.intended.on_iclcm(
            envelope.message, envelope.message.header.sample_time_s))
        self.ctx.every(1.0 / config.output_rate_hz, self.publish_scene)

    def stop(self) -> None:
        if getattr(self, "vehicle_bus", None) is not None:  # not there when start failed to open the interface
            self.vehicle_bus.close()

    def _sensor_handler(self, method_name: str):
        method = getattr(self.fusion, method_name)
        return lambda envelope: method(envelope.message)

    def on_ego(self, envelope: Envelope) -> None:
        if self.road_lanes is not None:
            self.road_lanes.on_ego(envelope.message)
        self.fusion.on_ego(envelope.message)

    def on_cam(self, envelope: Envelope) -> None:
        cam = envelope.message
        position = cam.reference_position
        if not (position.HasField("latitude_deg") and position.HasField("longitude_deg")):
            self.count("cam_without_position")
            return
        east, north, _ = self.plane.to_enu(position.latitude_deg, position.longitude_deg, self.origin[2])
        high = cam.high_frequency
        self.fusion.on_v2v(V2vObservation(
            station_id=cam.station_id, x_m=float(east), y_m=float(north),
            speed_mps=high.speed_mps if high.HasField("speed_mps") else float("nan"),
            heading_rad=high.heading_rad if high.HasField("heading_rad") else float("nan"),
            accel_mps2=high.longitudinal_acceleration_mps2 if high.HasField("longitudinal_acceleration_mps2") else 0.0,
            length_m=high.vehicle_length_m if high.HasField("vehicle_length_m") else 0.0,
            width_m=high.vehicle_width_m if high.HasField("vehicle_width_m") else 0.0,
            sample_time_s=cam.header.sample_time_s))

    def on_v2x_status(self, envelope: Envelope) -> None:
        """Security verdicts per station: packets with an invalid signature or an untrusted signer cost trust, an
        untrusted signer earns none. An unknown signer (its certificate not heard yet) says nothing against it."""
        time_s = envelope.message.header.sample_time_s
        for station in envelope.message.stations:
            if station.messages_signed:
                self.fusion.trust.on_security(
                    station.station_id, station.signature_failures + station.messages_untrusted,
                    station.messages_untrusted > 0 and not station.trusted, time_s)

    def publish_scene(self, now_s: float) -> None:
        scene = self.fusion.scene(now_s)
        self.intended.annotate(scene, now_s)
        self.counters.update(self.fusion.counters())
        self.counters.update(self.vehicle_bus.counts())
        self.ctx.publish("scene", scene, sample_time_s=now_s)
