"""Where the confirmed vehicles' bodies are. A reading inside one starts no new object.

A car ahead gives a radar several reflections: its rear face, its wheel arches and under-body, and multipath
ghosts that appear at or beyond it. Two objects cannot share a space, so an unmatched reading that lies inside a
tracked vehicle's body is that vehicle or a ghost of it, never a new object (the extended-object view of
Granstrom, Baum and Reuter, "Extended object tracking: introduction, overview and applications", 2017). A track
started from one would sit inside a car we follow, and a later short reading of that car could confirm it.
"""

from __future__ import annotations

import numpy as np

# Below this speed the velocity direction says nothing about heading.
MIN_SPEED_FOR_HEADING_MPS = 0.5


def inside_bodies(points_m: np.ndarray, rear_m: np.ndarray, velocity_mps: np.ndarray, length_m: np.ndarray,
                  width_m: np.ndarray, sensor_m: np.ndarray) -> np.ndarray:
    """(K,) whether each point (K, 2) lies inside some vehicle's body: from its rear bumper centre rear_m (M, 2)
    forward along its velocity (M, 2) by length_m (M,), width_m / 2 to each side. Only a vehicle moving away from
    the sensor at sensor_m (2,) shows it its rear: the face of one coming towards it (oncoming, or following
    behind) is its front, so where its body lies is not known, and it holds no point. Nor does a vehicle whose
    length or width is unknown (NaN), or that moves too slowly to give a heading."""
    speed_mps = np.linalg.norm(velocity_mps, axis=1)
    moving_away = np.einsum("mi,mi->m", rear_m - sensor_m, velocity_mps) > 0.0
    known = (speed_mps >= MIN_SPEED_FOR_HEADING_MPS) & moving_away & np.isfinite(length_m) & np.isfinite(width_m)
    if not known.any():
        return np.zeros(len(points_m), dtype=bool)
    forward = velocity_mps[known] / speed_mps[known, None]
    offset_m = points_m[:, None, :] - rear_m[None, known, :]
    along_m = offset_m[..., 0] * forward[:, 0] + offset_m[..., 1] * forward[:, 1]
    across_m = offset_m[..., 1] * forward[:, 0] - offset_m[..., 0] * forward[:, 1]
    inside = (along_m >= 0.0) & (along_m <= length_m[known]) & (np.abs(across_m) <= width_m[known] / 2.0)
    return inside.any(axis=1)


def nearest_body_point(rear_m: np.ndarray, heading_rad: float, length_m: float, width_m: float,
                       sensor_m: np.ndarray) -> np.ndarray:
    """(2,) the point of a vehicle's body nearest the sensor at sensor_m: the body runs from its rear bumper centre
    rear_m forward along heading_rad by length_m, width_m / 2 to each side. What a radar reports of a car that
    shows it its flank or a corner (the simulator's radar, and the strongest return of a real one)."""
    forward = np.array([np.cos(heading_rad), np.sin(heading_rad)])
    left = np.array([-forward[1], forward[0]])
    offset_m = sensor_m - rear_m
    along_m = min(max(float(offset_m @ forward), 0.0), length_m)
    across_m = min(max(float(offset_m @ left), -width_m / 2.0), width_m / 2.0)
    return rear_m + along_m * forward + across_m * left
