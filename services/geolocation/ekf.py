"""Ego-state EKF after DRIVERTIVE (GCDC 2016): state (eq. 6), observations (eq. 7), yaw rate from the rear
wheels (eq. 8), on ModelDrivenEkf (filterpy's equations, held to filterpy in the tests): the motion model steps
the state, driven by the step and the steering angle held over it, and angles are differenced by the update's
residual function.

GNSS position noise comes from the fix mode (Heudiasyc Table 1) and, when reported, the NMEA GST sigmas;
every update passes a chi-square gate on the normalised innovation squared (NIS) first.
"""

from __future__ import annotations

import enum
import math
from collections import Counter
from dataclasses import dataclass

import numpy as np
from scipy.special import gammaincinv

from coopdrive.services.geolocation.frames import LeverArm
from coopdrive.services.geolocation.model_driven_ekf import ModelDrivenEkf
from coopdrive.services.geolocation.motion_models import (
    ACCEL, ACCEL_BIAS, GNSS_ERROR_E, GNSS_ERROR_N, GNSS_TIME_ERROR, HEADING, SPEED, STATE_DIM, YAW_RATE,
    YAW_RATE_BIAS, CtraModel, E, MotionModel, N, ProcessNoise,
)
from coopdrive.v1 import gnss_pb2

# Heudiasyc Table 1 (NovAtel APN-051): expected horizontal accuracy per positioning mode, m.
# "~x" is taken as one sigma, "< x" as a two-sigma bound.
FIX_MODE_STD_M = {
    gnss_pb2.FIX_MODE_RTK_FIXED: 0.01,  # ~0.01 m
    gnss_pb2.FIX_MODE_RTK_FLOAT: 0.5,  # < 1.0 m
    gnss_pb2.FIX_MODE_DGPS: 1.0,  # < 2.0 m (PSRDIFF)
    gnss_pb2.FIX_MODE_SBAS: 3.0,  # ~3 m
    gnss_pb2.FIX_MODE_SINGLE: 5.0,  # ~5 m (PSRSP)
}
MAX_STEP_S = 0.02  # longer predictions are split so the linearisation stays good
# Zero-velocity update: how still "still" is, and the scales that turn it into yaw rate and acceleration
# uncertainties (a wheel-speed error over a car's half track, and over one odometry period).
ZUPT_SPEED_STD_MPS = 0.01
ZUPT_LEVER_M = 0.8
ZUPT_TIME_S = 0.1


class UpdateKind(enum.Enum):
    GNSS_POSITION = "gnss_position"
    ODOMETRY = "odometry"
    YAW_RATE = "yaw_rate"
    ACCEL = "accel"
    GNSS_SPEED = "gnss_speed"
    GNSS_HEADING = "gnss_heading"


@dataclass(frozen=True)
class EkfSnapshot:
    """All the filter's state, for going back in time (a late input is fused where it belongs, see latency.py)."""

    time_s: float | None
    x: np.ndarray
    P: np.ndarray
    steering_angle_rad: float
    accepted: Counter[UpdateKind]
    rejected: Counter[UpdateKind]


def gnss_position_std_m(fix_mode: int, gst_std_east_m: float = 0.0, gst_std_north_m: float = 0.0,
                        by_mode_m: dict[int, float] = FIX_MODE_STD_M) -> tuple[float, float] | None:
    """(std_east_m, std_north_m) for a fix: the receiver's GST sigmas, never below the mode's value (by_mode_m: the
    config's geolocator.gnss_fix_std_m)."""
    table_std_m = by_mode_m.get(fix_mode)
    if table_std_m is None:
        return None
    return max(gst_std_east_m, table_std_m), max(gst_std_north_m, table_std_m)


def _wrap(angle_rad: float) -> float:
    return (angle_rad + math.pi) % (2.0 * math.pi) - math.pi


def normalised_innovation_squared(y: np.ndarray, S: np.ndarray) -> float:
    """y^T S^-1 y, as y @ numpy.linalg.solve(S, y). For one row that solve is y / s to the bit
    (tests/geolocation/test_model_driven_ekf.py) at a tenth of its cost."""
    if len(y) == 1:
        return float(y[0] * (y[0] / S[0, 0]))
    return float(y @ np.linalg.solve(S, y))


def _residual(z: np.ndarray, hx: np.ndarray, angle_rows: tuple[int, ...] = ()) -> np.ndarray:
    """z - h(x), the angles among them wrapped (a heading of 179 deg against 181 deg is 2 deg off, not 358)."""
    y = z - hx
    for row in angle_rows:
        y[row] = _wrap(y[row])
    return y


def chi2_quantile(probability: float, dof: int) -> float:
    """The chi-square distribution's quantile, computed as scipy.stats.chi2.ppf does (without loading scipy.stats)."""
    return float(2.0 * gammaincinv(dof / 2.0, probability))


class GeolocationEkf:
    """The filter proper: predict to a time, then gated updates; knows nothing of messages or frames."""

    def __init__(self, model: MotionModel | None = None, gate_probability: float = 0.999,
                 error_by_fix_mode: bool = False) -> None:
        self.model = model or CtraModel(ProcessNoise())
        self.error_by_fix_mode = error_by_fix_mode
        self.kf = ModelDrivenEkf(self.model)
        self.time_s: float | None = None
        # The road-wheel steering angle, held until the next odometry sample (only the bicycle model reads it).
        self.steering_angle_rad = 0.0
        self.gate_probability = gate_probability
        self._gate_cache: dict[int, float] = {}
        self.accepted: Counter[UpdateKind] = Counter()
        self.rejected: Counter[UpdateKind] = Counter()
        self.last_nis: float = 0.0

    @property
    def initialised(self) -> bool:
        return self.time_s is not None

    @property
    def x(self) -> np.ndarray:
        return self.kf.x

    @property
    def P(self) -> np.ndarray:
        return self.kf.P

    def initialise(self, time_s: float, x0: np.ndarray, P0: np.ndarray) -> None:
        self.kf.x = np.asarray(x0, dtype=float).copy()
        self.kf.P = np.asarray(P0, dtype=float).copy()
        self.time_s = time_s

    def snapshot(self) -> EkfSnapshot:
        return EkfSnapshot(self.time_s, self.kf.x.copy(), self.kf.P.copy(), self.steering_angle_rad,
                           self.accepted.copy(), self.rejected.copy())

    def restore(self, snap: EkfSnapshot) -> None:
        """Back to a snapshot; one taken before initialise() makes the filter uninitialised again."""
        self.time_s = snap.time_s
        self.steering_angle_rad = snap.steering_angle_rad
        self.accepted, self.rejected = snap.accepted.copy(), snap.rejected.copy()
        if snap.time_s is not None:
            self.kf.x = snap.x.copy()
            self.kf.P = snap.P.copy()

    def hold_steering(self, steering_angle_rad: float) -> None:
        """The steering angle the predictions from now on are driven by (a zero-order hold of the wheels)."""
        self.steering_angle_rad = steering_angle_rad

    def update_counts(self) -> dict[str, int]:
        """Accepted and gated updates of each kind, for diagnostics."""
        counts = {f"accepted_{kind.value}": n for kind, n in self.accepted.items()}
        counts.update({f"gated_{kind.value}": n for kind, n in self.rejected.items()})
        return counts

    # --- prediction ----------------------------------------------------------------------------
    def predict_to(self, time_s: float) -> None:
        """Propagate to time_s in steps of at most MAX_STEP_S; earlier times are ignored."""
        remaining_s = time_s - self.time_s
        while remaining_s > 1e-9:
            dt = min(remaining_s, MAX_STEP_S)
            self.kf.predict(dt, self.steering_angle_rad)
            self.kf.x[HEADING] = _wrap(self.kf.x[HEADING])
            remaining_s -= dt
        self.time_s = max(self.time_s, time_s)

    def predicted(self, time_s: float) -> tuple[np.ndarray, np.ndarray]:
        """State and covariance at a later time, without moving the filter."""
        snap = self.snapshot()
        self.predict_to(time_s)
        x, P = self.kf.x.copy(), self.kf.P.copy()
        self.restore(snap)
        return x, P

    # --- updates -------------------------------------------------------------------------------
    def gate(self, dim_z: int) -> float:
        if dim_z not in self._gate_cache:
            self._gate_cache[dim_z] = chi2_quantile(self.gate_probability, dim_z)
        return self._gate_cache[dim_z]

    def _gated_update(self, kind: UpdateKind, z: np.ndarray, H: np.ndarray, hx: np.ndarray, R: np.ndarray,
                      angle_rows: tuple[int, ...] = (), soft: bool = False) -> bool:
        """soft: a measurement beyond the gate is not refused but fused with its noise inflated until it sits
        on the gate (for a receiver alone, whose speed and course are all there is: refusing one leaves the
        filter believing its own extrapolation, and the next one is further off still)."""
        y = _residual(z, hx, angle_rows)
        S = H @ self.kf.P @ H.T + R
        self.last_nis = normalised_innovation_squared(y, S)
        if self.last_nis > self.gate(len(z)):
            self.rejected[kind] += 1
            if not soft:
                return False
            R = R * (self.last_nis / self.gate(len(z)))
        # H and h(x) were taken at the state the update starts from, so they need not be computed again.
        self.kf.update(z, H, hx, R, residual=lambda z_, hx_: _residual(z_, hx_, angle_rows))
        self.kf.x[HEADING] = _wrap(self.kf.x[HEADING])
        self.accepted[kind] += 1
        return True

    def update_gnss_position(self, east_m: float, north_m: float, std_east_m: float, std_north_m: float,
                             lever_arm: LeverArm, time_jitter_s: float = 0.0, new_mode: bool = False) -> bool:
        """Antenna position = rear axle + R(heading) lever arm, plus the fixes' correlated error, less the way the
        antenna went in the time the fix's stamp is late (x[GNSS_TIME_ERROR]); z = [E, N] (eq. 7, first two rows).
        time_jitter_s: the white part of the stamp's error, a noise along the track of speed times it (it has no
        sideways part, so it is not added to both axes). new_mode: the fix's mode is not the last fused one's."""
        if new_mode and self.error_by_fix_mode:
            self._restart_gnss_error(max(std_east_m, std_north_m))
        x = self.kf.x
        antenna_east_m, antenna_north_m = lever_arm.antenna_position(x[E], x[N], x[HEADING])
        cos_h, sin_h = math.cos(x[HEADING]), math.sin(x[HEADING])
        late_m = x[SPEED] * x[GNSS_TIME_ERROR]
        hx = np.array([antenna_east_m + x[GNSS_ERROR_E] - late_m * cos_h,
                       antenna_north_m + x[GNSS_ERROR_N] - late_m * sin_h])
        H = np.zeros((2, STATE_DIM))
        H[0, E] = H[1, N] = H[0, GNSS_ERROR_E] = H[1, GNSS_ERROR_N] = 1.0
        H[:, HEADING] = lever_arm.d_antenna_d_heading(x[HEADING]) + late_m * np.array([sin_h, -cos_h])
        H[:, SPEED] = -x[GNSS_TIME_ERROR] * np.array([cos_h, sin_h])
        H[:, GNSS_TIME_ERROR] = -x[SPEED] * np.array([cos_h, sin_h])
        along = np.array([cos_h, sin_h])
        R = np.diag([std_east_m**2, std_north_m**2]) + (x[SPEED] * time_jitter_s) ** 2 * np.outer(along, along)
        return self._gated_update(UpdateKind.GNSS_POSITION, np.array([east_m, north_m]), H, hx, R)

    def _restart_gnss_error(self, fix_std_m: float) -> None:
        """A receiver that changes its fix mode computes another solution, whose correlated error is a new one of
        that mode's size (an RTK-float error correlated over a minute is not the RTK-fixed one's centimetre): the
        error state starts again at 0, uncorrelated, with the larger of the configured std and the fix's."""
        rows = [GNSS_ERROR_E, GNSS_ERROR_N]
        self.kf.x[rows] = 0.0
        self.kf.P[rows, :] = 0.0
        self.kf.P[:, rows] = 0.0
        self.kf.P[GNSS_ERROR_E, GNSS_ERROR_E] = self.kf.P[GNSS_ERROR_N, GNSS_ERROR_N] = max(
            self.model.noise.gnss_error_std_m, fix_std_m) ** 2

    def update_odometry(self, speed_mps: float, yaw_rate_radps: float, speed_std_mps: float,
                        yaw_rate_std_radps: float) -> bool:
        """z = [v, yaw_rate] (eq. 7, last two rows), yaw rate from the rear wheels (eq. 8)."""
        H = np.zeros((2, STATE_DIM))
        H[0, SPEED] = H[1, YAW_RATE] = 1.0
        hx = self.kf.x[[SPEED, YAW_RATE]]
        R = np.diag([speed_std_mps**2, yaw_rate_std_radps**2])
        return self._gated_update(UpdateKind.ODOMETRY, np.array([speed_mps, yaw_rate_radps]), H, hx, R)

    def update_speed(self, speed_mps: float, speed_std_mps: float, kind: UpdateKind = UpdateKind.ODOMETRY,
                     soft: bool = False) -> bool:
        H = np.zeros((1, STATE_DIM))
        H[0, SPEED] = 1.0
        return self._gated_update(kind, np.array([speed_mps]), H, self.kf.x[[SPEED]],
                                  np.array([[speed_std_mps**2]]), soft=soft)

    def update_heading(self, heading_rad: float, std_rad: float, soft: bool = False) -> bool:
        """A measured heading (dual-antenna receiver, or course over ground when moving), ENU radians."""
        H = np.zeros((1, STATE_DIM))
        H[0, HEADING] = 1.0
        return self._gated_update(UpdateKind.GNSS_HEADING, np.array([heading_rad]), H, self.kf.x[[HEADING]],
                                  np.array([[std_rad**2]]), angle_rows=(0,), soft=soft)

    def update_course(self, course_rad: float, std_rad: float, lever_arm: LeverArm, soft: bool = False) -> bool:
        """The receiver's course over ground, ENU radians: the direction the antenna moves, which is the heading
        turned by the antenna's own sideways speed in a turn. The antenna moves at (v - r y, r x) in the vehicle
        frame (rigid body, rear axle rolling without slip), so course = heading + atan2(r x, v - r y)."""
        x = self.kf.x
        along, across = x[SPEED] - x[YAW_RATE] * lever_arm.y_m, x[YAW_RATE] * lever_arm.x_m
        squared = along**2 + across**2
        H = np.zeros((1, STATE_DIM))
        H[0, HEADING] = 1.0
        if squared > 0.0:
            H[0, SPEED] = -across / squared
            H[0, YAW_RATE] = (lever_arm.x_m * along + lever_arm.y_m * across) / squared
        hx = np.array([x[HEADING] + math.atan2(across, along)])
        return self._gated_update(UpdateKind.GNSS_HEADING, np.array([course_rad]), H, hx, np.array([[std_rad**2]]),
                                  angle_rows=(0,), soft=soft)

    def update_yaw_rate(self, yaw_rate_radps: float, std_radps: float) -> bool:
        """The inertial unit's yaw rate: the vehicle's plus the unit's bias, z = r + b_r."""
        return self._update_inertial(UpdateKind.YAW_RATE, yaw_rate_radps, std_radps, YAW_RATE, YAW_RATE_BIAS)

    def update_accel(self, accel_mps2: float, std_mps2: float) -> bool:
        """The inertial unit's longitudinal acceleration, z = a + b_a."""
        return self._update_inertial(UpdateKind.ACCEL, accel_mps2, std_mps2, ACCEL, ACCEL_BIAS)

    def _update_inertial(self, kind: UpdateKind, value: float, std: float, row: int, bias_row: int) -> bool:
        H = np.zeros((1, STATE_DIM))
        H[0, row] = H[0, bias_row] = 1.0
        hx = np.array([self.kf.x[row] + self.kf.x[bias_row]])
        return self._gated_update(kind, np.array([value]), H, hx, np.array([[std**2]]))

    def zero_velocity_update(self, speed_std_mps: float = ZUPT_SPEED_STD_MPS) -> None:
        """The wheels stand still: speed, yaw rate and acceleration are zero, whatever the model predicted.
        (The inertial unit's biases stay: standing still, its readings are its biases, which is how they are
        learnt best.)

        An ungated pseudo-measurement (zero-velocity update). Without it a car braking to a stop keeps its
        negative acceleration state, its speed estimate runs below zero between odometry samples, and the
        gate then refuses the wheels' zeros as outliers: the estimate drives backwards on its own.
        """
        rows = [SPEED, YAW_RATE, ACCEL]
        self.kf.x[rows] = 0.0
        self.kf.P[rows, :] = 0.0
        self.kf.P[:, rows] = 0.0
        self.kf.P[SPEED, SPEED] = speed_std_mps**2
        self.kf.P[YAW_RATE, YAW_RATE] = (speed_std_mps / ZUPT_LEVER_M) ** 2
        self.kf.P[ACCEL, ACCEL] = (speed_std_mps / ZUPT_TIME_S) ** 2
        self.accepted[UpdateKind.ODOMETRY] += 1

    def reset_yaw_rate(self, measured_radps: float, std_radps: float, refused_s: float, by_imu: bool) -> None:
        """Take a measured yaw rate when the gate has refused it for refused_s (the car turned faster than the
        model's yaw acceleration allows). by_imu: the measurement includes the unit's bias, z = r + b_r."""
        x, P = self.kf.x, self.kf.P
        bias_var = P[YAW_RATE_BIAS, YAW_RATE_BIAS] if by_imu else 0.0
        yaw_rate = measured_radps - (x[YAW_RATE_BIAS] if by_imu else 0.0)
        # The heading integrated the old yaw rate meanwhile: it is off by up to the difference times the time.
        heading_var = (abs(yaw_rate - x[YAW_RATE]) * refused_s) ** 2
        x[YAW_RATE] = yaw_rate
        P[YAW_RATE, :] = 0.0
        P[:, YAW_RATE] = 0.0
        P[YAW_RATE, YAW_RATE] = std_radps**2 + bias_var
        P[YAW_RATE, YAW_RATE_BIAS] = P[YAW_RATE_BIAS, YAW_RATE] = -bias_var
        P[HEADING, HEADING] += heading_var

    def reset_position(self, east_m: float, north_m: float, std_m: float) -> None:
        """Jump to a position when the gate has refused the GNSS for too long (the filter was wrong): the fix
        less the correlated error the filter holds, uncertain by the fix's std and that error's."""
        rows = [E, N, GNSS_ERROR_E, GNSS_ERROR_N]
        error_var = self.kf.P[GNSS_ERROR_E, GNSS_ERROR_E]
        self.kf.x[E], self.kf.x[N] = east_m, north_m
        self.kf.x[[GNSS_ERROR_E, GNSS_ERROR_N]] = 0.0
        self.kf.P[rows, :] = 0.0
        self.kf.P[:, rows] = 0.0
        self.kf.P[E, E] = self.kf.P[N, N] = std_m**2 + error_var
        self.kf.P[GNSS_ERROR_E, GNSS_ERROR_E] = self.kf.P[GNSS_ERROR_N, GNSS_ERROR_N] = error_var
        # The position is the fix less its error: what the error is, the position is off by (P0 below too).
        self.kf.P[E, GNSS_ERROR_E] = self.kf.P[GNSS_ERROR_E, E] = -error_var
        self.kf.P[N, GNSS_ERROR_N] = self.kf.P[GNSS_ERROR_N, N] = -error_var
