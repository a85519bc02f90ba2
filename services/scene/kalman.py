"""The tracks' constant-acceleration Kalman filter, run on many tracks at once.

State [x, vx, ax, y, vy, ay] in ENU. Every function takes stacks, one row per track: means x (K, 6) and
covariances P (K, 6, 6), and applies the textbook equations to all rows in one numpy pass, so a frame's
updates cost a few array operations instead of one small filter call per track. The equations and their
order are those of filterpy's KalmanFilter (Labbe, "Kalman and Bayesian Filters in Python", ch. 6 "Multivariate
Kalman Filters"), which tests/scene/test_kalman.py holds this module to within 1e-9.
"""

from __future__ import annotations

from functools import lru_cache

import numpy as np

DIM = 6
IX, IVX, IAX, IY, IVY, IAY = range(DIM)
_IDENTITY = np.eye(DIM)
# Each axis's (position, speed, acceleration) block starts here.
_AXES = (IX, IY)
# Q's 3x3 block row by row: which power of t (index into t^5 .. t^1) over what.
_NOISE_POWERS = [0, 1, 2, 1, 2, 3, 2, 3, 4]
_NOISE_DIVISORS = np.array([20.0, 8.0, 6.0, 8.0, 3.0, 2.0, 6.0, 2.0, 1.0])
# A single track's steps (each V2V message, each step of a late one's replay) come back to a few time steps: a
# sensor's period, 0 for a reading at the track's own time (the kept ones served 80 % of v4's in an 8-stack string
# run). Their F and Q are kept, read-only, keyed by the bits of the step, so -0.0 keeps its own.
_ONE_STEP_CACHE_SIZE = 64


def transition(dt_s: np.ndarray) -> np.ndarray:
    """F (K, 6, 6) for each time step dt_s (K,): constant acceleration on each axis,
    p' = p + v dt + a dt^2 / 2, v' = v + a dt, a' = a."""
    dt_s = np.asarray(dt_s, dtype=float)
    if dt_s.size == 1:
        return _one_step(_transition, dt_s.tobytes(), None)
    return _transition(dt_s)


def _transition(dt_s: np.ndarray) -> np.ndarray:
    f = np.tile(_IDENTITY, (dt_s.size, 1, 1))
    for first in _AXES:
        f[:, first, first + 1] = dt_s
        f[:, first, first + 2] = 0.5 * dt_s * dt_s
        f[:, first + 1, first + 2] = dt_s
    return f


def process_noise(dt_s: np.ndarray, psd: float) -> np.ndarray:
    """Q (K, 6, 6) for each time step: white jerk of spectral density psd on each axis, the continuous
    white-noise model discretised over dt (Bar-Shalom, Li and Kirubarajan 2001, sect. 6.2.3; filterpy's
    Q_continuous_white_noise(dim=3)): block [[t^5/20, t^4/8, t^3/6], [t^4/8, t^3/3, t^2/2], [t^3/6, t^2/2, t]],
    written out because scipy's block_diag there costs more than the update."""
    dt_s = np.asarray(dt_s, dtype=float)
    if dt_s.size == 1:
        return _one_step(_process_noise, dt_s.tobytes(), psd)
    return _process_noise(dt_s, psd)


def _process_noise(dt_s: np.ndarray, psd: float) -> np.ndarray:
    t = np.abs(dt_s)
    t2 = t * t
    t3 = t2 * t
    powers = np.empty((t.size, 5))  # t^5 .. t^1
    powers[:, 0], powers[:, 1], powers[:, 2], powers[:, 3], powers[:, 4] = t3 * t2, t2 * t2, t3, t2, t
    block = psd * (powers[:, _NOISE_POWERS] / _NOISE_DIVISORS).reshape(t.size, 3, 3)
    q = np.zeros((t.size, DIM, DIM))
    for first in _AXES:
        q[:, first:first + 3, first:first + 3] = block
    return q


@lru_cache(maxsize=_ONE_STEP_CACHE_SIZE)
def _one_step(build, dt_bytes: bytes, psd: float | None) -> np.ndarray:
    """build's matrix (1, 6, 6) for the one time step whose float64 bits are dt_bytes, made once and read-only."""
    dt_s = np.frombuffer(dt_bytes, dtype=float)
    matrix = build(dt_s) if psd is None else build(dt_s, psd)
    matrix.flags.writeable = False
    return matrix


def predict(x: np.ndarray, p: np.ndarray, f: np.ndarray, q: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Prior of every row: x = F x, P = F P F^T + Q (Labbe ch. 6, "Prediction Equations")."""
    x = _times(f, x)
    p = f @ p @ f.transpose(0, 2, 1) + q
    return x, p


def update(x: np.ndarray, p: np.ndarray, z: np.ndarray, h: np.ndarray, r: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Posterior of every row given measurements z (K, m) = H x + noise of covariance R (K, m, m), with H (K, m, 6)
    (Labbe ch. 6, "Update Equations"):

        y = z - H x                               residual
        S = H P H^T + R                           system uncertainty in measurement space
        K = P H^T S^-1                            Kalman gain
        x = x + K y
        P = (I - K H) P (I - K H)^T + K R K^T     Joseph form: stays symmetric and positive definite
    """
    y = z - _times(h, x)
    pht = p @ h.transpose(0, 2, 1)
    s = h @ pht + r
    gain = pht @ np.linalg.inv(s)
    x = x + _times(gain, y)
    i_kh = _IDENTITY - gain @ h
    p = i_kh @ p @ i_kh.transpose(0, 2, 1) + gain @ r @ gain.transpose(0, 2, 1)
    return x, p


def _times(matrices: np.ndarray, vectors: np.ndarray) -> np.ndarray:
    """Each row's matrix times its vector: (K, a, b) and (K, b) -> (K, a)."""
    return (matrices @ vectors[..., None])[..., 0]


def predict_position(x: np.ndarray, p: np.ndarray, dt_s: np.ndarray, psd: float) -> tuple[np.ndarray, np.ndarray]:
    """Positions (K, 2) and their covariances (K, 2, 2) after dt_s: the position rows of predict() alone, for
    gating and for the scene, without building the full 6x6 prior."""
    f = np.stack((np.ones_like(dt_s), dt_s, 0.5 * dt_s * dt_s), axis=1)  # one axis's position row of F, (K, 3)
    return _predicted_rows(x, p, f, psd * np.abs(dt_s) ** 5 / 20.0)


def predict_velocity(x: np.ndarray, p: np.ndarray, dt_s: np.ndarray, psd: float) -> tuple[np.ndarray, np.ndarray]:
    """Velocities (K, 2) and their covariances (K, 2, 2) after dt_s: the velocity rows of predict() alone, for the
    radar's range-rate gate (doppler_gate.py)."""
    f = np.stack((np.zeros_like(dt_s), np.ones_like(dt_s), dt_s), axis=1)  # one axis's velocity row of F, (K, 3)
    return _predicted_rows(x, p, f, psd * np.abs(dt_s) ** 3 / 3.0)


def _predicted_rows(x: np.ndarray, p: np.ndarray, f: np.ndarray, q: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """One row of F per axis, f (K, 3) over (value, rate, acceleration), applied to both axes of x (K, 6) and p
    (K, 6, 6), with q (K,) that row's diagonal of Q: the predicted values (K, 2) and their covariances (K, 2, 2)."""
    values = np.stack((np.einsum("ki,ki->k", f, x[:, IX:IX + 3]), np.einsum("ki,ki->k", f, x[:, IY:IY + 3])), axis=1)
    cov = np.empty((len(x), 2, 2))
    cov[:, 0, 0] = np.einsum("ki,kij,kj->k", f, p[:, IX:IX + 3, IX:IX + 3], f) + q
    cov[:, 1, 1] = np.einsum("ki,kij,kj->k", f, p[:, IY:IY + 3, IY:IY + 3], f) + q
    cov[:, 0, 1] = cov[:, 1, 0] = np.einsum("ki,kij,kj->k", f, p[:, IX:IX + 3, IY:IY + 3], f)
    return values, cov


def velocity_stds(velocity_cov: np.ndarray, heading_rad: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Standard deviations (N,) of the velocity along heading_rad (N,) and across it, from velocity covariances
    (N, 2, 2): along it the speed's, across it divided by the speed the heading's to first order."""
    along = np.stack((np.cos(heading_rad), np.sin(heading_rad)), axis=1)
    across = np.stack((-along[:, 1], along[:, 0]), axis=1)
    along_var = np.einsum("ni,nij,nj->n", along, velocity_cov, along)
    across_var = np.einsum("ni,nij,nj->n", across, velocity_cov, across)
    return np.sqrt(np.maximum(along_var, 0.0)), np.sqrt(np.maximum(across_var, 0.0))
