"""Geolocation service: fuses GNSS fixes and CAN odometry into the ego state."""

from __future__ import annotations

import math

import pymap3d

from coopdrive.bus import Envelope
from coopdrive.runtime.service import Service, ServiceConfig
from coopdrive.v1 import ego_pb2, gnss_pb2


class GeolocationConfig(ServiceConfig):
    origin_lat_deg: float = 51.4758
    origin_lon_deg: float = 5.6247
    origin_alt_m: float = 20.0
    output_rate_hz: float = 50.0
    odometry_rate_hz: float = 100.0
    # Share of the GNSS innovation taken per fix by the complementary filter.
    gnss_gain: float = 0.3


class GeolocationService(Service):
    name = "geolocation"
    Config = GeolocationConfig

    def start(self) -> None:
        self.initialised = False
        self.x_m = self.y_m = self.heading_rad = 0.0
        self.speed_mps = self.yaw_rate_radps = self.accel_mps2 = 0.0
        self.last_time_s: float | None = None
        self.last_fix_mode = gnss_pb2.FIX_MODE_UNSPECIFIED
        self.ctx.subscribe("gnss/fix", self.on_gnss_fix)
        self.ctx.subscribe("vehicle/state", self.on_vehicle_state)
        self.ctx.every(1.0 / self.config.odometry_rate_hz, self.propagate)
        self.ctx.every(1.0 / self.config.output_rate_hz, self.publish_state)

    def on_gnss_fix(self, envelope: Envelope) -> None:
        fix = envelope.message
        c: GeolocationConfig = self.config
        east, north, _ = pymap3d.geodetic2enu(fix.latitude_deg, fix.longitude_deg, fix.altitude_m,
                                              c.origin_lat_deg, c.origin_lon_deg, c.origin_alt_m)
        self.last_fix_mode = fix.fix_mode
        if not self.initialised:
            self.x_m, self.y_m = float(east), float(north)
            self.heading_rad = math.radians(90.0 - fix.course_deg)
            self.initialised = True
            return
        self.x_m += c.gnss_gain * (float(east) - self.x_m)
        self.y_m += c.gnss_gain * (float(north) - self.y_m)
        self.count("gnss_fixes")

    def on_vehicle_state(self, envelope: Envelope) -> None:
        state = envelope.message
        speed = 0.5 * (state.wheel_speed_rear_left_mps + state.wheel_speed_rear_right_mps)
        self.yaw_rate_radps = state.yaw_rate_radps
        self.speed_mps = speed

    def propagate(self, now_s: float) -> None:
        if self.last_time_s is not None and self.initialised:
            dt = now_s - self.last_time_s
            self.heading_rad += self.yaw_rate_radps * dt
            self.x_m += self.speed_mps * math.cos(self.heading_rad) * dt
            self.y_m += self.speed_mps * math.sin(self.heading_rad) * dt
        self.last_time_s = now_s

    def publish_state(self, now_s: float) -> None:
        if not self.initialised:
            return
        state = ego_pb2.EgoState(x_m=self.x_m, y_m=self.y_m, heading_rad=self.heading_rad,
                                 speed_mps=self.speed_mps, yaw_rate_radps=self.yaw_rate_radps,
                                 mode=ego_pb2.LOCALISATION_MODE_GNSS_PRECISE, last_fix_mode=self.last_fix_mode)
        self.ctx.publish("ego/state", state)
