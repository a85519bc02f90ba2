"""The batched filter of kalman.py against filterpy's KalmanFilter, one filter per track, on the same sequences.

filterpy is the reference here only: the scene service itself does not import it.
"""

import math
import subprocess
import sys

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st
from filterpy.common import Q_continuous_white_noise
from filterpy.kalman import KalmanFilter

from coopdrive.services.scene import kalman
from coopdrive.services.scene.config import SceneFusionConfig
from coopdrive.services.scene.measurement import Measurement
from coopdrive.services.scene.tracker import Tracker
from coopdrive.v1 import header_pb2

TOLERANCE = 1e-9
PSD = 2.0


def constant_acceleration_f(dt_s):
    block = np.array([[1.0, dt_s, 0.5 * dt_s * dt_s], [0.0, 1.0, dt_s], [0.0, 0.0, 1.0]])
    return np.kron(np.eye(2), block)


def random_spd(rng, size, scale):
    a = rng.normal(size=(size, size))
    return scale * (a @ a.T + size * np.eye(size))


@pytest.mark.parametrize("dt_s", [0.0, 0.01, 0.05, 0.37])
def test_transition_and_process_noise_are_filterpys_constant_acceleration_white_jerk_model(dt_s):
    assert kalman.transition(np.array([dt_s]))[0] == pytest.approx(constant_acceleration_f(dt_s), abs=1e-15)
    expected = Q_continuous_white_noise(dim=3, dt=dt_s, spectral_density=PSD, block_size=2)
    assert kalman.process_noise(np.array([dt_s]), PSD)[0] == pytest.approx(expected, abs=1e-15)


@pytest.mark.parametrize("seed", [1, 2, 3])
def test_the_batched_filter_gives_filterpys_results_on_the_same_sequence(seed):
    rng = np.random.default_rng(seed)
    count = 7
    reference = []
    for _ in range(count):
        kf = KalmanFilter(dim_x=kalman.DIM, dim_z=2)
        kf.x, kf.P = rng.normal(scale=10.0, size=kalman.DIM), random_spd(rng, kalman.DIM, 0.5)
        reference.append(kf)
    x, p = np.array([kf.x for kf in reference]), np.array([kf.P for kf in reference])
    for _ in range(40):
        # Some tracks do not move on in time (a second sensor's frame at the same instant).
        dt_s = np.where(rng.random(count) < 0.2, 0.0, rng.uniform(0.0, 0.3, count))
        rows = int(rng.choice([2, 3, 5]))
        z, h, r = rng.normal(scale=10.0, size=(count, rows)), rng.normal(size=(count, rows, 6)), np.array(
            [random_spd(rng, rows, 0.1) for _ in range(count)])
        x, p = kalman.predict(x, p, kalman.transition(dt_s), kalman.process_noise(dt_s, PSD))
        x, p = kalman.update(x, p, z, h, r)
        for k, kf in enumerate(reference):
            kf.predict(F=constant_acceleration_f(dt_s[k]),
                       Q=Q_continuous_white_noise(dim=3, dt=dt_s[k], spectral_density=PSD, block_size=2))
            kf.update(z[k], R=r[k], H=h[k])
        np.testing.assert_allclose(x, [kf.x for kf in reference], rtol=0.0, atol=TOLERANCE)
        np.testing.assert_allclose(p, [kf.P for kf in reference], rtol=0.0, atol=TOLERANCE)


def radar_reading(time_s, x_m, y_m, radial_mps):
    los = np.array([x_m, y_m]) / math.hypot(x_m, y_m)
    return Measurement(source=header_pb2.SENSOR_SOURCE_RADAR, time_s=time_s, position_m=np.array([x_m, y_m]),
                       cov_m2=np.array([[0.09, 0.01], [0.01, 0.04]]), origin_m=np.zeros(2), radial_speed_mps=radial_mps,
                       radial_speed_std_mps=0.2, line_of_sight=los)


def test_a_trackers_frames_give_each_track_what_its_own_filterpy_filter_gives():
    """Many tracks updated by one batched step per frame, against the per-track filter the scene used to run:
    position and radial speed rows, R of closer readings divided by closer_bias."""
    config = SceneFusionConfig()
    rng = np.random.default_rng(5)
    tracker = Tracker(config)
    lanes = np.array([(20.0 + 25.0 * k, 4.0 * (k % 3 - 1), 15.0 + k) for k in range(6)])
    reference: dict[int, KalmanFilter] = {}
    for step in range(12):
        time_s = 0.05 * step
        frame = [radar_reading(time_s, x0 + speed * time_s + rng.normal(0.0, 0.1), y + rng.normal(0.0, 0.05),
                               speed + rng.normal(0.0, 0.2)) for x0, y, speed in lanes]
        tracker.process(frame)
        for track_id, meas in zip(sorted(tracker.tracks), frame, strict=True):
            if step == 0:
                reference[track_id] = filter_of(tracker.tracks[track_id])
            else:
                reference_step(reference[track_id], meas, 0.05, config.tracking.closer_bias)
    for track_id, track in tracker.tracks.items():
        np.testing.assert_allclose(track.mean, reference[track_id].x, rtol=0.0, atol=TOLERANCE)
        np.testing.assert_allclose(track.cov, reference[track_id].P, rtol=0.0, atol=TOLERANCE)


def filter_of(track):
    kf = KalmanFilter(dim_x=kalman.DIM, dim_z=2)
    kf.x, kf.P = track.mean.copy(), track.cov.copy()
    return kf


def reference_step(kf, meas, dt_s, closer_bias):
    kf.predict(F=constant_acceleration_f(dt_s),
               Q=Q_continuous_white_noise(dim=3, dt=dt_s, spectral_density=PSD, block_size=2))
    h = np.zeros((3, kalman.DIM))
    h[0, kalman.IX] = h[1, kalman.IY] = 1.0
    h[2, kalman.IVX], h[2, kalman.IVY] = meas.line_of_sight
    r = np.zeros((3, 3))
    closer = np.linalg.norm(meas.position_m) < math.hypot(kf.x[kalman.IX], kf.x[kalman.IY])
    r[:2, :2] = meas.cov_m2 / closer_bias if closer else meas.cov_m2
    r[2, 2] = meas.radial_speed_std_mps**2
    kf.update(np.array([*meas.position_m, meas.radial_speed_mps]), R=r, H=h)


def test_the_scene_service_imports_neither_filterpy_nor_scipy_stats():
    """filterpy pulls in scipy.stats, a good part of every scene process's start-up."""
    code = "import sys, coopdrive.services.scene.service; print('filterpy' in sys.modules, 'scipy.stats' in sys.modules)"
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, check=True).stdout
    assert out.split() == ["False", "False"]


def test_the_predicted_positions_and_velocities_are_those_rows_of_filterpy_s_predict():
    rng = np.random.default_rng(7)
    x = rng.normal(0.0, 5.0, (4, kalman.DIM))
    p = np.stack([random_spd(rng, kalman.DIM, 2.0) for _ in range(4)])
    dt_s = np.array([0.0, 0.04, 0.1, 0.3])
    positions, position_cov = kalman.predict_position(x, p, dt_s, PSD)
    velocities, velocity_cov = kalman.predict_velocity(x, p, dt_s, PSD)
    for k in range(4):
        kf = KalmanFilter(dim_x=kalman.DIM, dim_z=2)
        kf.x, kf.P = x[k].copy(), p[k].copy()
        kf.F = constant_acceleration_f(dt_s[k])
        kf.Q = np.kron(np.eye(2), Q_continuous_white_noise(dim=3, dt=dt_s[k], spectral_density=PSD))
        kf.predict()
        for rows, values, cov in (([kalman.IX, kalman.IY], positions, position_cov),
                                  ([kalman.IVX, kalman.IVY], velocities, velocity_cov)):
            assert values[k] == pytest.approx(kf.x[rows], abs=TOLERANCE)
            assert cov[k] == pytest.approx(kf.P[np.ix_(rows, rows)], abs=TOLERANCE)


@settings(max_examples=200, deadline=None)
@given(st.one_of(st.just(0.0), st.just(-0.0), st.sampled_from([0.02, 0.04, 0.05]),
                 st.floats(-5.0, 5.0, allow_nan=False)))
def test_a_single_steps_kept_f_and_q_are_the_ones_a_stack_of_steps_makes_to_the_bit(dt_s):
    # The same step in a stack of two is built afresh; alone it may come from the kept ones.
    alone_f, alone_q = kalman.transition(np.array([dt_s])), kalman.process_noise(np.array([dt_s]), PSD)
    stacked_f, stacked_q = kalman.transition(np.array([dt_s, 0.3])), kalman.process_noise(np.array([dt_s, 0.3]), PSD)
    assert alone_f.tobytes() == stacked_f[:1].tobytes() and alone_q.tobytes() == stacked_q[:1].tobytes()
    assert kalman.transition(np.array([dt_s])) is alone_f  # kept
    with pytest.raises(ValueError):
        alone_f[0, 0, 0] = 2.0  # read-only: a caller writing into it would change every later step's F
