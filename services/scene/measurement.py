"""Measurements in the local ENU frame, the ego pose they were taken from, and V2V observations.

Every front end turns a sensor frame into Measurement values: a position with its 2x2 covariance
at the sample time, plus whatever else that sensor knows (radial speed, velocity, class, ...).
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field

import numpy as np

from coopdrive.v1 import ego_pb2, sensors_pb2


@dataclass(frozen=True)
class V2vObservation:
    """One decoded CAM/iCLCM, already in the local frame (ENU metres, ENU heading)."""

    station_id: int
    x_m: float
    y_m: float
    speed_mps: float
    heading_rad: float
    accel_mps2: float
    length_m: float
    width_m: float
    sample_time_s: float


@dataclass(slots=True)
class Measurement:
    """One detection of one object by one source, ENU frame, rear-bumper reference point."""

    source: int  # header_pb2.SensorSource
    time_s: float
    position_m: np.ndarray  # (2,)
    cov_m2: np.ndarray  # (2, 2)
    # Sensor origin in ENU at time_s; bearings and ranges for gating are taken from here.
    origin_m: np.ndarray
    # Radar: absolute speed along the line of sight from origin_m, positive away.
    radial_speed_mps: float | None = None
    radial_speed_std_mps: float = 0.0
    # Unit ENU line of sight the radial speed was measured along (to the reflection point, which need
    # not be the reference point in position_m).
    line_of_sight: np.ndarray | None = None
    # V2V: full velocity and acceleration vectors.
    velocity_mps: np.ndarray | None = None
    velocity_std_mps: float = 0.0
    accel_mps2: float | None = None
    heading_rad: float | None = None
    accel_std_mps2: float = 0.0
    length_m: float | None = None
    width_m: float | None = None
    object_class: int = sensors_pb2.OBJECT_CLASS_UNSPECIFIED
    station_id: int | None = None
    # Camera detections carry their own detector score; 1 for the rest.
    quality: float = 1.0
    # A reading that refines a known object's filter but neither announces a new object nor vouches for
    # one (a flank cut by the edge of the LiDAR's field of view).
    ambiguous: bool = False
    extras: dict = field(default_factory=dict)


@dataclass(frozen=True)
class EgoPose:
    """Ego rear-axle pose in ENU with the position covariance and the motion used to shift it in time."""

    time_s: float
    x_m: float
    y_m: float
    heading_rad: float
    speed_mps: float
    yaw_rate_radps: float
    accel_mps2: float
    position_cov_m2: np.ndarray

    @classmethod
    def from_state(cls, ego: ego_pb2.EgoState) -> EgoPose:
        """The pose of an EgoState; ValueError naming the field when it is not a number."""
        for name in ("x_m", "y_m", "heading_rad", "speed_mps", "yaw_rate_radps", "accel_mps2"):
            if not math.isfinite(getattr(ego, name)):
                raise ValueError(f"ego state {name} is {getattr(ego, name)}")
        cov = np.zeros((2, 2))
        covariance = ego.covariance
        if len(covariance) >= 36:
            # The 6x6 row-major covariance: only its east/north block is needed, four of 36 numbers.
            block = [covariance[0], covariance[1], covariance[6], covariance[7]]
            if all(math.isfinite(value) for value in block):
                cov = np.array(block).reshape(2, 2)
        elif ego.position_std_m > 0.0:
            cov = np.eye(2) * ego.position_std_m**2
        return cls(
            time_s=ego.header.sample_time_s,
            x_m=ego.x_m,
            y_m=ego.y_m,
            heading_rad=ego.heading_rad,
            speed_mps=ego.speed_mps,
            yaw_rate_radps=ego.yaw_rate_radps,
            accel_mps2=ego.accel_mps2,
            position_cov_m2=cov,
        )

    def at(self, time_s: float) -> EgoPose:
        """This pose moved along a constant speed and yaw-rate arc to time_s."""
        dt = time_s - self.time_s
        if dt == 0.0:
            return self
        heading = self.heading_rad + self.yaw_rate_radps * dt
        mid = self.heading_rad + 0.5 * self.yaw_rate_radps * dt
        distance = self.speed_mps * dt + 0.5 * self.accel_mps2 * dt * dt
        return EgoPose(
            time_s=time_s,
            x_m=self.x_m + distance * math.cos(mid),
            y_m=self.y_m + distance * math.sin(mid),
            heading_rad=heading,
            speed_mps=self.speed_mps + self.accel_mps2 * dt,
            yaw_rate_radps=self.yaw_rate_radps,
            accel_mps2=self.accel_mps2,
            position_cov_m2=self.position_cov_m2,
        )

    @property
    def position_m(self) -> np.ndarray:
        return np.array([self.x_m, self.y_m])

    @property
    def velocity_mps(self) -> np.ndarray:
        return self.speed_mps * np.array([math.cos(self.heading_rad), math.sin(self.heading_rad)])

    def rotation(self) -> np.ndarray:
        c, s = math.cos(self.heading_rad), math.sin(self.heading_rad)
        return np.array([[c, -s], [s, c]])

    def to_enu(self, x_vehicle_m: float, y_vehicle_m: float) -> np.ndarray:
        return self.position_m + self.rotation() @ np.array([x_vehicle_m, y_vehicle_m])

    def points_to_enu(self, points_vehicle_m: np.ndarray) -> np.ndarray:
        """to_enu of K points (K, 2) at once."""
        return self.position_m + points_vehicle_m @ self.rotation().T

    def to_vehicle(self, point_enu_m: np.ndarray) -> np.ndarray:
        return self.rotation().T @ (np.asarray(point_enu_m, dtype=float) - self.position_m)


def polar_cov_vehicle(range_m: float, bearing_rad: float, range_std_m: float, bearing_std_rad: float) -> np.ndarray:
    """Covariance of a (range, bearing) reading mapped to Cartesian vehicle coordinates."""
    return polar_covs_vehicle(np.array([range_m]), np.array([bearing_rad]), range_std_m, bearing_std_rad)[0]


def polar_covs_vehicle(range_m: np.ndarray, bearing_rad: np.ndarray, range_std_m, bearing_std_rad) -> np.ndarray:
    """polar_cov_vehicle of K readings at once (K, 2, 2): J diag(range_std^2, bearing_std^2) J^T with J the
    Jacobian of (x, y) with respect to (range, bearing); the standard deviations scalars or one per reading."""
    c, s = np.cos(bearing_rad), np.sin(bearing_rad)
    jac = np.stack((np.stack((c, -range_m * s), axis=-1), np.stack((s, range_m * c), axis=-1)), axis=-2)
    variances = np.zeros((len(range_m), 2, 2))
    variances[:, 0, 0] = np.square(range_std_m)
    variances[:, 1, 1] = np.square(bearing_std_rad)
    return jac @ variances @ jac.transpose(0, 2, 1)


def cov_to_enu(pose: EgoPose, cov_vehicle_m2: np.ndarray) -> np.ndarray:
    """A vehicle-frame covariance in ENU, including the ego's own position uncertainty."""
    rot = pose.rotation()
    return rot @ cov_vehicle_m2 @ rot.T + pose.position_cov_m2
