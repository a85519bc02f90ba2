"""Scene service: turns sensor objects into the fused object list with the most-important objects."""

from __future__ import annotations

import math

from coopdrive.bus import Envelope
from coopdrive.runtime.service import Service, ServiceConfig
from coopdrive.v1 import header_pb2, scene_pb2


class SceneConfig(ServiceConfig):
    output_rate_hz: float = 25.0
    # Ego geometry: distance from the rear axle to the front bumper.
    ego_front_bumper_m: float = 3.5
    ego_lane_half_width_m: float = 1.75
    radar_fade_time_s: float = 0.3


class SceneService(Service):
    name = "scene"
    Config = SceneConfig

    def start(self) -> None:
        self.ego = None
        self.radar = None
        self.ctx.subscribe("ego/state", self.on_ego)
        self.ctx.subscribe("radar/tracks", self.on_radar)
        self.ctx.every(1.0 / self.config.output_rate_hz, self.publish_scene)

    def on_ego(self, envelope: Envelope) -> None:
        self.ego = envelope.message

    def on_radar(self, envelope: Envelope) -> None:
        self.radar = envelope.message

    def publish_scene(self, now_s: float) -> None:
        if self.ego is None:
            return
        c: SceneConfig = self.config
        scene = scene_pb2.Scene()
        ego = self.ego
        radar_fresh = self.radar is not None and now_s - self.radar.header.sample_time_s <= c.radar_fade_time_s
        best = None
        for track in self.radar.tracks if radar_fresh else ():
            forward = track.range_m * math.cos(track.azimuth_rad)
            left = track.range_m * math.sin(track.azimuth_rad)
            obj = scene.objects.add(object_id=track.track_id)
            obj.position.x_m = ego.x_m + forward * math.cos(ego.heading_rad) - left * math.sin(ego.heading_rad)
            obj.position.y_m = ego.y_m + forward * math.sin(ego.heading_rad) + left * math.cos(ego.heading_rad)
            obj.position.confidence = 1.0
            obj.position.sources.append(header_pb2.SENSOR_SOURCE_RADAR)
            obj.position.valid_until_s = self.radar.header.sample_time_s + c.radar_fade_time_s
            obj.speed_mps.value = ego.speed_mps + track.range_rate_mps
            obj.speed_mps.confidence = 1.0
            obj.speed_mps.sources.append(header_pb2.SENSOR_SOURCE_RADAR)
            obj.width_m.value = track.width_m
            obj.longitudinal_gap_m = forward - c.ego_front_bumper_m
            obj.lateral_offset_m = left
            obj.relative_speed_mps = track.range_rate_mps
            obj.v2v_trust = 1.0
            if abs(left) <= c.ego_lane_half_width_m and (best is None or forward < best[0]):
                best = (forward, track.track_id)
        if best is not None:
            scene.has_forward_mio = scene.has_mio = True
            scene.forward_mio_id = scene.mio_id = best[1]
        self.ctx.publish("scene", scene, sample_time_s=self.radar.header.sample_time_s if radar_fresh else now_s)
