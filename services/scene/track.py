"""One tracked object: a constant-acceleration Kalman filter with out-of-sequence replay.

State [x, vx, ax, y, vy, ay] in ENU. Every applied measurement is logged with the posterior after
it for replay_window_s; a measurement older than the filter time (V2V arrives late) is inserted
in time order and the log is replayed from the posterior just before it (buffer-and-replay), so the
late reading counts exactly as if it had arrived on time.
"""

from __future__ import annotations

import bisect
import enum
import math
from dataclasses import dataclass

import numpy as np
from filterpy.kalman import KalmanFilter

from coopdrive.v1 import header_pb2

from .config import TrackingConfig
from .measurement import Measurement
from .properties import ObjectProperties

_DIM = 6
_IX, _IVX, _IAX, _IY, _IVY, _IAY = range(_DIM)
# Sources whose position fixes are our own ranging, used to judge what V2V stations claim.
RANGING_SOURCES = (header_pb2.SENSOR_SOURCE_LIDAR, header_pb2.SENSOR_SOURCE_RADAR)


class TrackStatus(enum.Enum):
    TENTATIVE = 1
    CONFIRMED = 2
    DELETED = 3


def transition(dt: float) -> np.ndarray:
    block = np.array([[1.0, dt, 0.5 * dt * dt], [0.0, 1.0, dt], [0.0, 0.0, 1.0]])
    f = np.zeros((_DIM, _DIM))
    f[:3, :3] = block
    f[3:, 3:] = block
    return f


def process_noise(dt: float, psd: float) -> np.ndarray:
    """White-jerk noise of a constant-acceleration axis, the same as filterpy's
    Q_continuous_white_noise(dim=3), written out because scipy's block_diag there costs more than the
    whole Kalman update."""
    t = abs(dt)
    t2, t3 = t * t, t * t * t
    q = psd * np.array([[t3 * t2 / 20.0, t2 * t2 / 8.0, t3 / 6.0], [t2 * t2 / 8.0, t3 / 3.0, t2 / 2.0], [t3 / 6.0, t2 / 2.0, t]])
    out = np.zeros((_DIM, _DIM))
    out[:3, :3] = q
    out[3:, 3:] = q
    return out


def predict_positions(tracks: list[Track], time_s: float, psd: float) -> tuple[np.ndarray, np.ndarray]:
    """Positions (M, 2) and their covariances (M, 2, 2) of many tracks at time_s in one numpy pass;
    the same numbers as Track.predicted, for gating."""
    x = np.array([t.mean for t in tracks])
    p = np.array([t.cov for t in tracks])
    dt = time_s - np.array([t.time_s for t in tracks])
    f = np.stack((np.ones_like(dt), dt, 0.5 * dt * dt), axis=1)  # (M, 3)
    xy = np.stack((np.einsum("mi,mi->m", f, x[:, :3]), np.einsum("mi,mi->m", f, x[:, 3:])), axis=1)
    q = psd * np.abs(dt) ** 5 / 20.0
    cov = np.empty((len(tracks), 2, 2))
    cov[:, 0, 0] = np.einsum("mi,mij,mj->m", f, p[:, :3, :3], f) + q
    cov[:, 1, 1] = np.einsum("mi,mij,mj->m", f, p[:, 3:, 3:], f) + q
    cov[:, 0, 1] = cov[:, 1, 0] = np.einsum("mi,mij,mj->m", f, p[:, :3, 3:], f)
    return xy, cov


@dataclass
class _Logged:
    measurement: Measurement
    x: np.ndarray
    p: np.ndarray


@dataclass
class RangingFix:
    """Latest LiDAR or radar position of this object, to compare V2V claims with."""

    time_s: float
    position_m: np.ndarray


class Track:
    def __init__(self, track_id: int, first: Measurement, config: TrackingConfig, properties: ObjectProperties):
        self.track_id = track_id
        self.status = TrackStatus.TENTATIVE
        self.first_seen_s = first.time_s
        self.last_hit_s = first.time_s
        # The first reading is the prior itself: position from it, motion unknown unless it says.
        self.hits = 0
        self.station_id: int | None = None
        self.ranging_fix: RangingFix | None = None
        self.props = properties
        self._config = config
        self._kf = KalmanFilter(dim_x=_DIM, dim_z=2)
        x0 = np.zeros(_DIM)
        x0[_IX], x0[_IY] = first.position_m
        p0 = np.diag([0.0, cfg_sq(config.initial_speed_std_mps), cfg_sq(config.initial_accel_std_mps2)] * 2)
        p0[np.ix_([_IX, _IY], [_IX, _IY])] = first.cov_m2
        if first.velocity_mps is not None:
            x0[_IVX], x0[_IVY] = first.velocity_mps
            p0[_IVX, _IVX] = p0[_IVY, _IVY] = first.velocity_std_mps**2
        elif first.radial_speed_mps is not None:
            x0[[_IVX, _IVY]] = first.radial_speed_mps * _line_of_sight(first)
        self._kf.x = x0
        self._kf.P = p0
        self.time_s = first.time_s
        self._base = (first.time_s, x0.copy(), p0.copy())
        self._log: list[_Logged] = []
        self.replays = 0
        self._note_hit(first)

    # -- state -----------------------------------------------------------------------------

    def predicted(self, time_s: float) -> tuple[np.ndarray, np.ndarray]:
        """Mean and covariance at time_s without touching the filter (works backwards too)."""
        dt = time_s - self.time_s
        f = transition(dt)
        return f @ self._kf.x, f @ self._kf.P @ f.T + process_noise(dt, self._config.jerk_psd_m2ps5)

    @property
    def mean(self) -> np.ndarray:
        return self._kf.x

    @property
    def cov(self) -> np.ndarray:
        return self._kf.P

    @staticmethod
    def position_of(x: np.ndarray) -> np.ndarray:
        return np.array([x[_IX], x[_IY]])

    @staticmethod
    def velocity_of(x: np.ndarray) -> np.ndarray:
        return np.array([x[_IVX], x[_IVY]])

    @staticmethod
    def accel_of(x: np.ndarray) -> np.ndarray:
        return np.array([x[_IAX], x[_IAY]])

    @staticmethod
    def position_cov_of(p: np.ndarray) -> np.ndarray:
        return np.array([[p[_IX, _IX], p[_IX, _IY]], [p[_IY, _IX], p[_IY, _IY]]])

    # -- measurements ---------------------------------------------------------------------

    def apply(self, meas: Measurement) -> bool:
        """Fuse one measurement, in or out of sequence. False when it is older than the replay log."""
        if meas.time_s >= self.time_s:
            self._filter_update(meas)
            self._log.append(_Logged(meas, self._kf.x.copy(), self._kf.P.copy()))
            self._trim()
            self._note_hit(meas)
            return True
        times = [entry.measurement.time_s for entry in self._log]
        index = bisect.bisect_right(times, meas.time_s)
        if index == 0 and meas.time_s < self._base[0]:
            return False
        start_time, start_x, start_p = self._base
        if index > 0:
            prior = self._log[index - 1]
            start_time, start_x, start_p = prior.measurement.time_s, prior.x, prior.p
        self._kf.x, self._kf.P, self.time_s = start_x.copy(), start_p.copy(), start_time
        replay = [meas] + [entry.measurement for entry in self._log[index:]]
        del self._log[index:]
        for item in replay:
            self._filter_update(item)
            self._log.append(_Logged(item, self._kf.x.copy(), self._kf.P.copy()))
        self.replays += 1
        self._note_hit(meas)
        return True

    def _note_hit(self, meas: Measurement) -> None:
        if meas.ambiguous:
            return  # refines the filter, but neither confirms the track nor fixes where it is
        self.hits += 1
        self.last_hit_s = max(self.last_hit_s, meas.time_s)
        if meas.source in RANGING_SOURCES and (self.ranging_fix is None or meas.time_s >= self.ranging_fix.time_s):
            self.ranging_fix = RangingFix(meas.time_s, meas.position_m.copy())

    def _trim(self) -> None:
        horizon = self.time_s - self._config.replay_window_s
        drop = 0
        while drop < len(self._log) - 1 and self._log[drop].measurement.time_s < horizon:
            drop += 1
        if drop:
            last = self._log[drop - 1]
            self._base = (last.measurement.time_s, last.x, last.p)
            del self._log[:drop]

    def _filter_update(self, meas: Measurement) -> None:
        dt = meas.time_s - self.time_s
        if dt > 0.0:
            self._kf.F = transition(dt)
            self._kf.Q = process_noise(dt, self._config.jerk_psd_m2ps5)
            self._kf.predict()
        self.time_s = max(self.time_s, meas.time_s)
        rows, values, variances = self._measurement_rows(meas)
        h = np.array(rows)
        r = np.zeros((len(rows), len(rows)))
        cov = meas.cov_m2.copy()
        predicted_range = float(np.linalg.norm(self.position_of(self._kf.x) - meas.origin_m))
        measured_range = float(np.linalg.norm(meas.position_m - meas.origin_m))
        if measured_range < predicted_range:
            cov = cov / self._config.closer_bias  # Chalmers 4.3.1: bias for closer readings
        r[:2, :2] = cov
        for i, variance in enumerate(variances, start=2):
            r[i, i] = variance
        self._kf.update(np.array(values), R=r, H=h)

    def _measurement_rows(self, meas: Measurement) -> tuple[list, list, list]:
        rows = [_unit(_IX), _unit(_IY)]
        values = [meas.position_m[0], meas.position_m[1]]
        variances: list[float] = []
        if meas.radial_speed_mps is not None:
            los = _line_of_sight(meas)
            rows.append(los[0] * _unit(_IVX) + los[1] * _unit(_IVY))
            values.append(meas.radial_speed_mps)
            variances.append(meas.radial_speed_std_mps**2)
        if meas.velocity_mps is not None:
            rows += [_unit(_IVX), _unit(_IVY)]
            values += [meas.velocity_mps[0], meas.velocity_mps[1]]
            variances += [meas.velocity_std_mps**2] * 2
        if meas.accel_mps2 is not None and meas.heading_rad is not None:
            c, s = math.cos(meas.heading_rad), math.sin(meas.heading_rad)
            rows.append(c * _unit(_IAX) + s * _unit(_IAY))
            values.append(meas.accel_mps2)
            variances.append(meas.accel_std_mps2**2)
        return rows, values, variances


def _line_of_sight(meas: Measurement) -> np.ndarray:
    if meas.line_of_sight is not None:
        return meas.line_of_sight
    los = meas.position_m - meas.origin_m
    return los / max(float(np.linalg.norm(los)), 1e-6)


def _unit(index: int) -> np.ndarray:
    e = np.zeros(_DIM)
    e[index] = 1.0
    return e


def cfg_sq(value: float) -> float:
    return value * value
