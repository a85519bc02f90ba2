"""FrameGeometry: one sensor frame's readings against the tracks, as the tracker's association sees them: the tracks'
states predicted to the frame's time, the faces of them the sensor sees, the gating costs, a radar frame's
range-rate terms, and whether a reading lies inside a vehicle already known."""

from __future__ import annotations

from typing import NamedTuple

import numpy as np

from coopdrive.messages.unknowns import DEFAULT_LENGTH_M
from coopdrive.v1 import header_pb2

from . import kalman
from .association import polar_cost_matrix
from .config import SceneFusionConfig
from .doppler_gate import PairTerms, range_rate_terms
from .front_faces import facing_sensor, front_offsets, heading_known
from .kalman import IAX, IAY, IVX, IVY, IX, IY
from .measurement import Measurement
from .occupancy import inside_bodies
from .properties import LENGTH, WIDTH
from .support_table import SupportTable
from .track import Track, stacked_states

_V2V = header_pb2.SENSOR_SOURCE_V2V


def _predicted_means(tracks: list[Track], time_s: float) -> np.ndarray:
    """The tracks' means (M, 6) predicted to time_s."""
    x, _ = stacked_states(tracks)
    dt_s = time_s - np.array([t.time_s for t in tracks])
    return np.einsum("mij,mj->mi", kalman.transition(dt_s), x)


class Prior(NamedTuple):
    """The tracks' stacked means (M, 6) and covariances (M, 6, 6), the time from each to time_s, and their positions
    (M, 2) with covariances (M, 2, 2) predicted to it."""

    x: np.ndarray
    p: np.ndarray
    dt_s: np.ndarray
    position_m: np.ndarray
    position_cov: np.ndarray
    time_s: float


class FrameGeometry:
    def __init__(self, config: SceneFusionConfig, properties: SupportTable) -> None:
        self._config = config
        self.properties = properties

    def range_rate_terms_of(self, measurements: list[Measurement], prior: Prior | None) -> PairTerms | None:
        """A radar frame's range-rate gate and costs against the tracks' velocities at its time (doppler_gate.py);
        None for other frames, without predicting a velocity."""
        if prior is None or all(meas.radial_speed_mps is None for meas in measurements):
            return None
        cfg = self._config.tracking
        velocity_mps, velocity_cov = kalman.predict_velocity(prior.x, prior.p, prior.dt_s, cfg.jerk_psd_m2ps5)
        return range_rate_terms(measurements, velocity_mps, velocity_cov, cfg.doppler_gate_chi2,
                                cfg.doppler_gate_min_mps)

    def inside_vehicles(self, confirmed: list[Track], measurements: list[Measurement]) -> np.ndarray:
        """Whether each of one frame's readings lies inside one of the `confirmed` vehicles' bodies at the frame's
        time."""
        if not confirmed:
            return np.zeros(len(measurements), dtype=bool)
        x = _predicted_means(confirmed, measurements[0].time_s)
        sizes = self.properties.values([t.props.row for t in confirmed])
        return inside_bodies(np.array([m.position_m for m in measurements]), x[:, [IX, IY]], x[:, [IVX, IVY]],
                             sizes[:, LENGTH], sizes[:, WIDTH], measurements[0].origin_m)

    def prior(self, tracks: list[Track], time_s: float) -> Prior:
        """The tracks' stacked means and covariances and their positions predicted to time_s, worked out once per
        frame for the front faces and the gating."""
        x, p = stacked_states(tracks)
        dt_s = time_s - np.array([t.time_s for t in tracks])
        position_m, position_cov = kalman.predict_position(x, p, dt_s, self._config.tracking.jerk_psd_m2ps5)
        return Prior(x, p, dt_s, position_m, position_cov, time_s)

    def front_faces(self, tracks: list[Track], prior: Prior | None, sensor_m: np.ndarray) -> np.ndarray:
        """(M, 2) from each track's rear to the face the sensor at sensor_m sees (front_faces.py). A track that shows
        its front for the first time and was started from what sensors saw of that front is moved back to its rear,
        once; one V2V holds is at its rear already."""
        if not tracks:
            return np.zeros((0, 2))
        x, p, dt_s = prior.x, prior.p, prior.dt_s
        velocity_mps = np.stack((x[:, IVX] + x[:, IAX] * dt_s, x[:, IVY] + x[:, IAY] * dt_s), axis=1)
        # Rows and columns IVX and IVY: a view, where a list index would copy.
        velocity_cov = p[:, IVX::IVY - IVX, IVX::IVY - IVX]
        config = self._config.tracking.front_faces
        known = heading_known(velocity_mps, velocity_cov, config)
        direction = velocity_mps / np.maximum(np.hypot(velocity_mps[:, 0], velocity_mps[:, 1]), 1e-9)[:, None]
        was_facing = np.fromiter((t.shows_front for t in tracks), dtype=bool, count=len(tracks))
        facing = facing_sensor(prior.position_m, direction, known, sensor_m, was_facing, config)
        for k in np.flatnonzero(facing & ~known):  # facing on an earlier frame's word: the direction it had then
            direction[k] = tracks[k].direction
        for k in np.flatnonzero(facing & known):
            tracks[k].direction = direction[k]
        offsets_m = np.zeros((len(tracks), 2))
        shown = np.flatnonzero(facing)
        if shown.size:
            lengths_m = self.properties.values([tracks[k].props.row for k in shown])[:, LENGTH]
            offsets_m[shown] = front_offsets(direction[shown], lengths_m, np.ones(shown.size, dtype=bool),
                                             DEFAULT_LENGTH_M)
        for k in np.flatnonzero(facing != was_facing):
            track = tracks[k]
            track.shows_front = bool(facing[k])
            if track.shows_front and not track.moved_to_rear:
                track.moved_to_rear = True
                if _V2V not in track.props.position.sources(prior.time_s):
                    track.move(-offsets_m[k])
        return offsets_m

    def geometry(self, measurements: list[Measurement], tracks: list[Track],
                  prior: Prior | None = None, front_m: np.ndarray | None = None) -> tuple[np.ndarray, ...]:
        """Measurement positions, covariances and sensor origins, and the tracks' predicted positions and
        covariances at the measurements' time (prior's where given); with front_m (M, 2), the positions of the faces
        the sensor sees."""
        meas_xy = np.array([m.position_m for m in measurements])
        meas_cov = np.array([m.cov_m2 for m in measurements])
        origins = np.array([m.origin_m for m in measurements])
        if tracks:
            prior = prior if prior is not None else self.prior(tracks, measurements[0].time_s)
            track_xy, track_cov = prior.position_m, prior.position_cov
            if front_m is not None:
                track_xy = track_xy + front_m
        else:
            track_xy, track_cov = np.zeros((0, 2)), np.zeros((0, 2, 2))
        return meas_xy, meas_cov, origins, track_xy, track_cov

    def costs(self, measurements: list[Measurement], tracks: list[Track]) -> tuple[np.ndarray, np.ndarray]:
        """Squared Mahalanobis distances and innovation log-determinants, measurements x tracks."""
        if not tracks:
            return np.zeros((len(measurements), 0)), np.zeros((len(measurements), 0))
        return polar_cost_matrix(*self.geometry(measurements, tracks), self._config.tracking.angle_emphasis,
                                 with_log_det=True)
