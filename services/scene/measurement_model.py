"""What a measurement says about a track's state: the z, H and R of its Kalman update, for many at once.

Every measurement gives the position (two rows); a radar adds its radial speed along the line of sight, a V2V
message its velocity (two rows) and its acceleration along its heading. Measurements with the same rows form
one stack: z (K, m), H (K, m, 6), R (K, m, m).
"""

from __future__ import annotations

import numpy as np

from .kalman import DIM, IAX, IAY, IVX, IVY, IX, IY
from .measurement import Measurement

# Which rows beyond the position: (radial speed, velocity, acceleration along the heading).
Layout = tuple[bool, bool, bool]


def layout_of(meas: Measurement) -> Layout:
    return (meas.radial_speed_mps is not None, meas.velocity_mps is not None,
            meas.accel_mps2 is not None and meas.heading_rad is not None)


def line_of_sight(meas: Measurement) -> np.ndarray:
    """Unit ENU direction the radial speed was measured along: given by the radar, else origin to position."""
    if meas.line_of_sight is not None:
        return meas.line_of_sight
    los = meas.position_m - meas.origin_m
    return los / max(float(np.linalg.norm(los)), 1e-6)


def measurement_model(measurements: list[Measurement], layout: Layout, prior_xy_m: np.ndarray,
                      closer_bias: float) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """z, H and R of measurements that share one layout, against the tracks' prior positions (K, 2)."""
    radial, velocity, accel = layout
    rows = 2 + radial + 2 * velocity + accel
    count = len(measurements)
    z, h, r = np.zeros((count, rows)), np.zeros((count, rows, DIM)), np.zeros((count, rows, rows))
    positions_m = np.array([m.position_m for m in measurements])
    z[:, :2] = positions_m
    h[:, 0, IX] = h[:, 1, IY] = 1.0
    r[:, :2, :2] = _position_noise(measurements, positions_m, prior_xy_m, closer_bias)
    row = 2
    if radial:
        los = np.array([line_of_sight(m) for m in measurements])
        h[:, row, IVX], h[:, row, IVY] = los[:, 0], los[:, 1]
        z[:, row] = [m.radial_speed_mps for m in measurements]
        r[:, row, row] = [m.radial_speed_std_mps**2 for m in measurements]
        row += 1
    if velocity:
        h[:, row, IVX] = h[:, row + 1, IVY] = 1.0
        z[:, row:row + 2] = [m.velocity_mps for m in measurements]
        r[:, row, row] = r[:, row + 1, row + 1] = [m.velocity_std_mps**2 for m in measurements]
        row += 2
    if accel:
        heading = np.array([m.heading_rad for m in measurements])
        h[:, row, IAX], h[:, row, IAY] = np.cos(heading), np.sin(heading)
        z[:, row] = [m.accel_mps2 for m in measurements]
        r[:, row, row] = [m.accel_std_mps2**2 for m in measurements]
    return z, h, r


def _position_noise(measurements: list[Measurement], positions_m: np.ndarray, prior_xy_m: np.ndarray,
                    closer_bias: float) -> np.ndarray:
    """The readings' position covariances, divided by closer_bias where the reading is nearer the sensor than
    the track is predicted to be (Chalmers 4.3.1: distance is updated "with a bias for closer readings")."""
    cov = np.array([m.cov_m2 for m in measurements])
    origins = np.array([m.origin_m for m in measurements])
    # Squared ranges compare as the ranges do.
    closer = np.square(positions_m - origins).sum(axis=1) < np.square(prior_xy_m - origins).sum(axis=1)
    return cov / np.where(closer, closer_bias, 1.0)[:, None, None]
