"""One tracked object: a constant-acceleration Kalman filter with out-of-sequence replay.

State [x, vx, ax, y, vy, ay] in ENU (kalman.py). Every applied measurement is logged with the posterior after
it for replay_window_s; a measurement older than the filter time (V2V arrives late) is inserted
in time order and the log is replayed from the posterior just before it (buffer-and-replay), so the
late reading counts exactly as if it had arrived on time. A frame's in-sequence measurements are filtered
for all their tracks at once (filter_steps) and handed to each track with accept().
"""

from __future__ import annotations

import bisect
import enum
from dataclasses import dataclass, replace

import numpy as np

from coopdrive.v1 import header_pb2

from . import kalman
from .config import TrackingConfig
from .kalman import DIM, IAX, IAY, IVX, IVY, IX, IY
from .measurement import Measurement
from .measurement_model import Layout, layout_of, line_of_sight, measurement_model
from .properties import ObjectProperties

# Sources whose position fixes are our own ranging, used to judge what V2V stations claim.
RANGING_SOURCES = (header_pb2.SENSOR_SOURCE_LIDAR, header_pb2.SENSOR_SOURCE_RADAR)


class TrackStatus(enum.Enum):
    TENTATIVE = 1
    CONFIRMED = 2
    DELETED = 3


def predict_positions(tracks: list[Track], time_s: float, psd: float) -> tuple[np.ndarray, np.ndarray]:
    """Positions (M, 2) and their covariances (M, 2, 2) of many tracks at time_s in one numpy pass;
    the same numbers as Track.predicted, for gating."""
    x, p = stacked_states(tracks)
    return kalman.predict_position(x, p, time_s - np.array([t.time_s for t in tracks]), psd)


def stacked_states(tracks: list[Track]) -> tuple[np.ndarray, np.ndarray]:
    """The tracks' means (M, 6) and covariances (M, 6, 6)."""
    return np.array([t.mean for t in tracks]), np.array([t.cov for t in tracks])


def filter_steps(tracks: list[Track], measurements: list[Measurement],
                 config: TrackingConfig) -> tuple[np.ndarray, np.ndarray]:
    """Posterior means (K, 6) and covariances (K, 6, 6) of tracks[k] after measurements[k], each at or after its
    track's time: every track predicted to its measurement's time and updated with it, all in one pass."""
    x, p = stacked_states(tracks)
    dt_s = np.array([m.time_s for m in measurements]) - np.array([t.time_s for t in tracks])
    return _filtered(x, p, dt_s, measurements, config)


def _filtered(x: np.ndarray, p: np.ndarray, dt_s: np.ndarray, measurements: list[Measurement],
              config: TrackingConfig) -> tuple[np.ndarray, np.ndarray]:
    """filter_steps on the tracks' stacked means (K, 6), covariances (K, 6, 6) and time steps (K,)."""
    # A step of dt 0 leaves the state as it is (F = I, Q = 0), so no track needs to skip the prediction.
    x, p = kalman.predict(x, p, kalman.transition(dt_s), kalman.process_noise(dt_s, config.jerk_psd_m2ps5))
    groups: dict[Layout, list[int]] = {}
    for k, meas in enumerate(measurements):
        groups.setdefault(layout_of(meas), []).append(k)
    if len(groups) == 1:  # one layout (always so for one track's step): every row at once, none to pick out
        return kalman.update(x, p, *measurement_model(measurements, next(iter(groups)), x[:, [IX, IY]],
                                                      config.closer_bias))
    for layout, rows in groups.items():
        z, h, r = measurement_model([measurements[k] for k in rows], layout, x[rows][:, [IX, IY]], config.closer_bias)
        x[rows], p[rows] = kalman.update(x[rows], p[rows], z, h, r)
    return x, p


@dataclass(slots=True)
class _Logged:
    measurement: Measurement
    x: np.ndarray
    p: np.ndarray


@dataclass(slots=True)
class RangingFix:
    """Latest LiDAR or radar position of this object, to compare V2V claims with, and where its sensor was."""

    time_s: float
    position_m: np.ndarray
    origin_m: np.ndarray


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
        # LiDAR and radar readings that counted as hits.
        self.ranging_hits = 0
        self.props = properties
        # Whether its sensors see its front (front_faces.py), and whether its state, started from a face they saw,
        # was moved back to its rear once it showed them that face.
        self.shows_front = False
        self.moved_to_rear = False
        # The unit vector it last moved along while the filter knew where it pointed (zero before that).
        self.direction = np.zeros(2)
        self._config = config
        x0 = np.zeros(DIM)
        x0[IX], x0[IY] = first.position_m
        p0 = np.diag([0.0, cfg_sq(config.initial_speed_std_mps), cfg_sq(config.initial_accel_std_mps2)] * 2)
        p0[np.ix_([IX, IY], [IX, IY])] = first.cov_m2
        if first.velocity_mps is not None:
            x0[IVX], x0[IVY] = first.velocity_mps
            p0[IVX, IVX] = p0[IVY, IVY] = first.velocity_std_mps**2
        elif first.radial_speed_mps is not None:
            x0[[IVX, IVY]] = first.radial_speed_mps * line_of_sight(first)
        # Means and covariances are replaced, never written in place: the log and a frame's stacks share them.
        self._x, self._p = x0, p0
        self.time_s = first.time_s
        self._base = (first.time_s, x0, p0)
        self._log: list[_Logged] = []
        self.replays = 0
        self._note_hit(first)

    # -- state -----------------------------------------------------------------------------

    def predicted(self, time_s: float) -> tuple[np.ndarray, np.ndarray]:
        """Mean and covariance at time_s without touching the filter (works backwards too)."""
        dt_s = np.array([time_s - self.time_s])
        x, p = kalman.predict(self._x[None], self._p[None], kalman.transition(dt_s),
                              kalman.process_noise(dt_s, self._config.jerk_psd_m2ps5))
        return x[0], p[0]

    def predicted_mean(self, time_s: float) -> np.ndarray:
        """The mean alone at time_s (predicted's first half, without the covariance)."""
        return kalman.transition(np.array([time_s - self.time_s]))[0] @ self._x

    @property
    def mean(self) -> np.ndarray:
        return self._x

    @property
    def cov(self) -> np.ndarray:
        return self._p

    @staticmethod
    def position_of(x: np.ndarray) -> np.ndarray:
        return np.array([x[IX], x[IY]])

    @staticmethod
    def velocity_of(x: np.ndarray) -> np.ndarray:
        return np.array([x[IVX], x[IVY]])

    @staticmethod
    def accel_of(x: np.ndarray) -> np.ndarray:
        return np.array([x[IAX], x[IAY]])

    @staticmethod
    def position_cov_of(p: np.ndarray) -> np.ndarray:
        return np.array([[p[IX, IX], p[IX, IY]], [p[IY, IX], p[IY, IY]]])

    def move(self, offset_m: np.ndarray) -> None:
        """Move the object by offset_m (2,) in its state, its replay log and its ranging fix alike: the point its
        sensors saw was not its rear. Logged V2V readings already gave the rear and stay."""
        def moved(x: np.ndarray) -> np.ndarray:
            x = x.copy()
            x[IX] += offset_m[0]
            x[IY] += offset_m[1]
            return x

        self._x = moved(self._x)
        self._base = (self._base[0], moved(self._base[1]), self._base[2])
        for entry in self._log:
            entry.x = moved(entry.x)
            if entry.measurement.source != header_pb2.SENSOR_SOURCE_V2V:
                entry.measurement = replace(entry.measurement, position_m=entry.measurement.position_m + offset_m)
        if self.ranging_fix is not None:
            self.ranging_fix.position_m = self.ranging_fix.position_m + offset_m

    def take_motion(self, other: Track, variance_scale: float) -> None:
        """Fuse other's velocity and acceleration, the same vehicle known another way (its station's CAMs), into
        this track's as one measurement of them, their covariance scaled by variance_scale (1/trust^2 for a
        station): a track our sensors have just started knows the motion only as the filter's first guess, and
        with that guess it neither gates its next readings nor agrees with the station. The replay log is left
        as it is: a replay from before this re-derives the motion from its readings, the station's among them."""
        rows = [IVX, IAX, IVY, IAY]
        x_other, p_other = other.predicted(self.time_s)
        h = np.eye(DIM)[rows]
        x, p = kalman.update(self._x[None], self._p[None], x_other[rows][None], h[None],
                             (p_other[np.ix_(rows, rows)] * variance_scale)[None])
        self._x, self._p = x[0], p[0]

    # -- measurements ---------------------------------------------------------------------

    def apply(self, meas: Measurement) -> bool:
        """Fuse one measurement, in or out of sequence. False when it is older than the replay log."""
        if meas.time_s >= self.time_s:
            self.accept(meas, *self._step(meas))
            return True
        times = [entry.measurement.time_s for entry in self._log]
        index = bisect.bisect_right(times, meas.time_s)
        if index == 0 and meas.time_s < self._base[0]:
            return False
        self.time_s, self._x, self._p = self._base
        if index > 0:
            prior = self._log[index - 1]
            self.time_s, self._x, self._p = prior.measurement.time_s, prior.x, prior.p
        replay = [meas] + [entry.measurement for entry in self._log[index:]]
        del self._log[index:]
        for item in replay:
            self._x, self._p = self._step(item)
            self.time_s = max(self.time_s, item.time_s)
            self._log.append(_Logged(item, self._x, self._p))
        self.replays += 1
        self._note_hit(meas)
        return True

    def accept(self, meas: Measurement, x: np.ndarray, p: np.ndarray) -> None:
        """Take the posterior x, p after an in-sequence measurement (filter_steps computes it for many tracks)."""
        self._x, self._p = x, p
        self.time_s = max(self.time_s, meas.time_s)
        self._log.append(_Logged(meas, x, p))
        self._trim()
        self._note_hit(meas)

    def _step(self, meas: Measurement) -> tuple[np.ndarray, np.ndarray]:
        """filter_steps of this track alone: the same kernels on its state as a stack of one, so the same bits."""
        x, p = _filtered(self._x[None], self._p[None], np.array([meas.time_s - self.time_s]), [meas], self._config)
        return x[0], p[0]

    def _note_hit(self, meas: Measurement) -> None:
        if meas.ambiguous:
            return  # refines the filter, but neither confirms the track nor fixes where it is
        self.hits += 1
        self.last_hit_s = max(self.last_hit_s, meas.time_s)
        if meas.source not in RANGING_SOURCES:
            return
        self.ranging_hits += 1
        if self.ranging_fix is None:
            self.ranging_fix = RangingFix(meas.time_s, meas.position_m.copy(), meas.origin_m)
        elif meas.time_s >= self.ranging_fix.time_s:
            # Moved on in place: a fix per track and frame would be that much more for the garbage collector.
            fix = self.ranging_fix
            fix.time_s, fix.position_m, fix.origin_m = meas.time_s, meas.position_m.copy(), meas.origin_m

    def _trim(self) -> None:
        horizon = self.time_s - self._config.replay_window_s
        if self._log[0].measurement.time_s >= horizon:
            return
        drop = 0
        while drop < len(self._log) - 1 and self._log[drop].measurement.time_s < horizon:
            drop += 1
        if drop:
            last = self._log[drop - 1]
            self._base = (last.measurement.time_s, last.x, last.p)
            del self._log[:drop]


def cfg_sq(value: float) -> float:
    return value * value
