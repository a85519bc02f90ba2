"""Hand-made sensor frames for the scene tests: a straight road along +x (east), ego at y = 0."""

from __future__ import annotations

import math

import numpy as np

from coopdrive.services.scene.measurement import V2vObservation
from coopdrive.v1 import ego_pb2, sensors_pb2

LIDAR_RESOLUTION_RAD = math.radians(0.5)
LIDAR_MAX_RANGE_M = 80.0


def ego_state(time_s: float, x_m: float = 0.0, speed_mps: float = 0.0, y_m: float = 0.0) -> ego_pb2.EgoState:
    ego = ego_pb2.EgoState(x_m=x_m, y_m=y_m, heading_rad=0.0, speed_mps=speed_mps)
    ego.header.sample_time_s = time_s
    return ego


def lidar_scan(time_s: float, boxes: list[tuple[float, float, float]], ego_x_m: float = 0.0,
               omit_misses: bool = False) -> sensors_pb2.LidarScan:
    """One-layer scan seeing the rear faces of boxes (rear x ENU, centre y, width), ego heading east.
    Misses read max range, or are left out of the scan as the simulator does with omit_misses."""
    scan = sensors_pb2.LidarScan(max_range_m=LIDAR_MAX_RANGE_M)
    scan.header.sample_time_s = time_s
    layer = scan.layers.add(layer=2, elevation_rad=0.0)
    for azimuth in np.arange(-0.5, 0.5, LIDAR_RESOLUTION_RAD):
        hit = LIDAR_MAX_RANGE_M
        for rear_x, centre_y, width in boxes:
            distance = rear_x - ego_x_m
            if distance <= 0.0:
                continue
            lateral = distance * math.tan(azimuth)
            if abs(lateral - centre_y) <= 0.5 * width:
                hit = min(hit, distance / math.cos(azimuth))
        if omit_misses and hit >= LIDAR_MAX_RANGE_M:
            continue
        layer.azimuth_rad.append(float(azimuth))
        layer.range_m.append(float(hit))
    return scan


def nearest_face_y(centre_y_m: float, width_m: float = 1.8) -> float:
    """Lateral position of the point of a rear face nearest to our x axis."""
    return centre_y_m - math.copysign(min(abs(centre_y_m), 0.5 * width_m), centre_y_m)


def radar_tracks(time_s: float, objects: list[tuple[float, float, float]], ego_x_m: float = 0.0,
                 ego_speed_mps: float = 0.0) -> sensors_pb2.RadarTracks:
    """Radar tracks for 1.8 m wide objects (rear x ENU, centre y, speed along x), reported like the
    simulator's radar at the point of the rear face nearest to us."""
    frame = sensors_pb2.RadarTracks()
    frame.header.sample_time_s = time_s
    for index, (x_m, centre_y_m, speed_mps) in enumerate(objects, start=1):
        y_m = nearest_face_y(centre_y_m)
        dx = x_m - ego_x_m
        rng = math.hypot(dx, y_m)
        frame.tracks.add(track_id=index, range_m=rng, azimuth_rad=math.atan2(y_m, dx),
                         range_rate_mps=(speed_mps - ego_speed_mps) * dx / rng, width_m=1.8)
    return frame


def v2v(time_s: float, station_id: int, rear_x_m: float, y_m: float, speed_mps: float,
        accel_mps2: float = 0.0, length_m: float = 4.5) -> V2vObservation:
    """A CAM from a vehicle heading east whose rear bumper is at (rear_x_m, y_m)."""
    return V2vObservation(station_id=station_id, x_m=rear_x_m + length_m, y_m=y_m, speed_mps=speed_mps,
                          heading_rad=0.0, accel_mps2=accel_mps2, length_m=length_m, width_m=1.8,
                          sample_time_s=time_s)


class Road:
    """Ego at 10 m/s along +x; sensors fed on a common 20 Hz tick, lidar every other tick."""

    EGO_SPEED_MPS = 10.0
    TICK_S = 0.05

    def ego_x(self, time_s: float) -> float:
        return self.EGO_SPEED_MPS * time_s

    def ego(self, time_s: float) -> ego_pb2.EgoState:
        return ego_state(time_s, x_m=self.ego_x(time_s), speed_mps=self.EGO_SPEED_MPS)

    def __init__(self, fusion, omit_misses: bool = False):
        self.fusion = fusion
        self.omit_misses = omit_misses

    def sense(self, time_s: float, objects: list[tuple[float, float, float]], lidar: bool = True,
              radar: bool = True) -> None:
        """objects: (rear x ENU, y, speed) as our LiDAR and radar see them at time_s."""
        ego = self.ego(time_s)
        self.fusion.on_ego(ego)
        if lidar and round(time_s / self.TICK_S) % 2 == 0:
            boxes = [(x, y, 1.8) for x, y, _ in objects]
            scan = lidar_scan(time_s, boxes, ego_x_m=self.ego_x(time_s), omit_misses=self.omit_misses)
            self.fusion.on_lidar(scan, ego)
        if radar:
            self.fusion.on_radar(radar_tracks(time_s, objects, ego_x_m=self.ego_x(time_s),
                                              ego_speed_mps=self.EGO_SPEED_MPS), ego)

    def ticks(self, start_s: float, end_s: float):
        count = round((end_s - start_s) / self.TICK_S)
        return [round(start_s + k * self.TICK_S, 6) for k in range(count)]
