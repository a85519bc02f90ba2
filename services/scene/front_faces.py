"""Which tracked vehicles show our sensors their front, and how far ahead of their rear that front is.

A LiDAR, radar, camera or sonar reports the face of a vehicle nearest to it; the scene tracks rear bumpers (a
CAM's reference point, the centre of the front, moved back by the vehicle's length). For a vehicle driving away
from the sensor that face is its rear. One coming towards it (oncoming, or following behind us) shows its front,
a length ahead of its rear: taken for the rear, an oncoming car sat a car length nearer than its own CAMs put it,
so its station never linked to what our sensors saw and the car was two objects (the extended-object view of
Granstrom, Baum and Reuter, "Extended object tracking: introduction, overview and applications", 2017).

Whether a vehicle faces the sensor is read from its velocity: within facing_angle_rad of the line from it to the
sensor. It stops facing past release_angle_rad (it is beside us, showing its flank); in between, below
min_speed_mps where the velocity says nothing of the heading (a car waiting at the junction), and while the
filter's heading is less certain than max_heading_std_rad (a track a few readings old, whose velocity is still
its prior's), the last answer stands.
"""

from __future__ import annotations

import numpy as np

from .config import FrontFaceConfig


def heading_known(velocity_mps: np.ndarray, velocity_cov: np.ndarray, config: FrontFaceConfig) -> np.ndarray:
    """(M,) whether each velocity (M, 2), known to covariance velocity_cov (M, 2, 2), says where the vehicle points:
    fast enough, and its direction certain enough. The heading's variance is the velocity's across it over the
    speed squared (kalman.velocity_stds), written out here because this runs for every track on every frame."""
    vx, vy = velocity_mps[:, 0], velocity_mps[:, 1]
    speed2 = vx * vx + vy * vy
    # Variance across the velocity times speed^2: (-vy, vx) P (-vy, vx)^T.
    across_var_speed2 = (vy * vy * velocity_cov[:, 0, 0] - 2.0 * vx * vy * velocity_cov[:, 0, 1]
                         + vx * vx * velocity_cov[:, 1, 1])
    return (speed2 >= config.min_speed_mps ** 2) & (across_var_speed2 <= config.max_heading_std_rad ** 2 * speed2 * speed2)


def facing_sensor(rear_m: np.ndarray, direction: np.ndarray, known: np.ndarray, sensor_m: np.ndarray,
                  was_facing: np.ndarray, config: FrontFaceConfig) -> np.ndarray:
    """(M,) whether each vehicle, rear bumper centre rear_m (M, 2) pointing along the unit vector direction (M, 2)
    where known (M,), shows the sensor at sensor_m (2,) its front; was_facing (M,) is the answer of the frame
    before, which stands where the direction is not known."""
    to_sensor_m = sensor_m - rear_m
    distance_m = np.linalg.norm(to_sensor_m, axis=1)
    cos_angle = np.einsum("mi,mi->m", direction, to_sensor_m) / np.maximum(distance_m, 1e-9)
    facing = known & (cos_angle >= np.cos(config.facing_angle_rad))
    turned_away = known & (cos_angle < np.cos(config.release_angle_rad))
    return facing | (np.asarray(was_facing, dtype=bool) & ~turned_away)


def front_offsets(direction: np.ndarray, length_m: np.ndarray, facing: np.ndarray,
                  default_length_m: float) -> np.ndarray:
    """(M, 2) from each vehicle's rear to the face its sensors see: its length along its unit direction (M, 2) where
    it faces them (default_length_m where its length is unknown, NaN), nothing where it does not."""
    length_m = np.where(np.isfinite(length_m), length_m, default_length_m)
    return direction * np.where(facing, length_m, 0.0)[:, None]
