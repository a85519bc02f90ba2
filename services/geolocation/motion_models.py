"""Motion models over the DRIVERTIVE state x = [E, N, heading, v, yaw_rate, a] (eq. 6), augmented with the
inertial unit's yaw-rate and acceleration biases [b_r, b_a] (constant but for a slow random walk; Groves,
"Principles of GNSS, Inertial, and Multisensor Integrated Navigation Systems", 2nd ed., sect. 14.2.6) and the
GNSS position's time-correlated error [b_E, b_N] (first-order Gauss-Markov, Groves sect. 14.2.7 and 3.4.3:
b(t + dt) = exp(-dt / tau) b(t) + w, var(w) = sigma^2 (1 - exp(-2 dt / tau))); sigma 0 leaves it out) and the
error of the fixes' time stamps [dt_fix] (the receiver's latency as configured against as it is, plus the host's
arrival-time resolution: a fix stamped dt_fix late shows where the antenna was dt_fix earlier), Gauss-Markov
alike: a Schmidt-style nuisance state the filter estimates only where the speed changes, and otherwise carries
as the along-track uncertainty it is.

Each model returns the propagated state, its Jacobian F and the process noise Q for one step dt, given the step's
input (the road-wheel steering angle, held over the step; the filter owns it, see ekf.py).
- CTRA (constant turn rate and acceleration), the model of the DRIVERTIVE EKF: position integrated at the
  mid-step heading and speed, which is exact to second order in dt.
- Kinematic bicycle, rear-axle reference point, driven by the road-wheel steering angle:
  yaw_rate = v tan(delta) / L (Chalmers kinematic single-track model).
"""

from __future__ import annotations

import enum
import math
from dataclasses import dataclass

import numpy as np

(E, N, HEADING, SPEED, YAW_RATE, ACCEL, YAW_RATE_BIAS, ACCEL_BIAS, GNSS_ERROR_E, GNSS_ERROR_N,
 GNSS_TIME_ERROR) = range(11)
STATE_DIM = 11
# The vehicle's own state, the part the EgoState message carries (its covariance among it).
VEHICLE_STATE_DIM = 6
MAX_CACHED_STEPS = 64


class MotionModelKind(enum.Enum):
    CTRA = "ctra"
    KINEMATIC_BICYCLE = "kinematic_bicycle"


@dataclass(frozen=True)
class ProcessNoise:
    """Continuous white-noise spectral densities driving the model."""

    jerk_std_mps3: float = 0.5
    yaw_accel_std_radps2: float = 0.02
    position_std_mps: float = 0.02  # unmodelled slip, per sqrt(s)
    steering_std_rad: float = 0.002  # bicycle model: steering angle noise
    # Random walk of the inertial unit's biases (bias instability), per sqrt(s).
    yaw_rate_bias_walk_radps: float = 1e-4
    accel_bias_walk_mps2: float = 1e-3
    # The GNSS fixes' time-correlated error: its steady-state std (0: none, the fixes' errors are white) and
    # correlation time.
    gnss_error_std_m: float = 0.0
    gnss_error_time_s: float = 60.0
    # The fixes' time-stamp error: its steady-state std (0: the stamps are taken as exact) and correlation time.
    gnss_time_error_std_s: float = 0.0
    gnss_time_error_time_s: float = 600.0

    def gnss_error_decay(self, dt: float) -> float:
        return math.exp(-dt / self.gnss_error_time_s)

    def gnss_time_error_decay(self, dt: float) -> float:
        return math.exp(-dt / self.gnss_time_error_time_s)


def _set_integrated_pair(Q: np.ndarray, integral: int, value: int, q: float, dt: float) -> None:
    """Writes the covariance of (integral, value) of a random walk with spectral density q over dt into Q:
    q [[dt^3/3, dt^2/2], [dt^2/2, dt]]. Element by element, as cheap for one step as a cached matrix."""
    Q[integral, integral] = q * (dt**3 / 3.0)
    Q[integral, value] = Q[value, integral] = q * (dt**2 / 2.0)
    Q[value, value] = q * dt


def _add_bias_walk(Q: np.ndarray, noise: ProcessNoise, dt: float) -> None:
    Q[YAW_RATE_BIAS, YAW_RATE_BIAS] = noise.yaw_rate_bias_walk_radps**2 * dt
    Q[ACCEL_BIAS, ACCEL_BIAS] = noise.accel_bias_walk_mps2**2 * dt
    Q[GNSS_ERROR_E, GNSS_ERROR_E] = Q[GNSS_ERROR_N, GNSS_ERROR_N] = (
        noise.gnss_error_std_m**2 * -math.expm1(-2.0 * dt / noise.gnss_error_time_s))
    Q[GNSS_TIME_ERROR, GNSS_TIME_ERROR] = noise.gnss_time_error_std_s**2 * -math.expm1(
        -2.0 * dt / noise.gnss_time_error_time_s)


def _gnss_error_step(noise: ProcessNoise, x: np.ndarray, dt: float, F: np.ndarray, x_new: np.ndarray) -> None:
    """The fixes' correlated error and their time stamps' error decay towards zero (Gauss-Markov)."""
    decay = noise.gnss_error_decay(dt)
    x_new[GNSS_ERROR_E], x_new[GNSS_ERROR_N] = decay * x[GNSS_ERROR_E], decay * x[GNSS_ERROR_N]
    F[GNSS_ERROR_E, GNSS_ERROR_E] = F[GNSS_ERROR_N, GNSS_ERROR_N] = decay
    time_decay = noise.gnss_time_error_decay(dt)
    x_new[GNSS_TIME_ERROR] = time_decay * x[GNSS_TIME_ERROR]
    F[GNSS_TIME_ERROR, GNSS_TIME_ERROR] = time_decay


def _position_step(x: np.ndarray, yaw_rate: float, dt: float, F: np.ndarray, x_new: np.ndarray) -> None:
    """Mid-point position update and its partial derivatives, shared by both models."""
    heading_mid = x[HEADING] + 0.5 * yaw_rate * dt
    speed_mid = x[SPEED] + 0.5 * x[ACCEL] * dt
    cos_h, sin_h = math.cos(heading_mid), math.sin(heading_mid)
    x_new[E] = x[E] + speed_mid * cos_h * dt
    x_new[N] = x[N] + speed_mid * sin_h * dt
    F[E, HEADING] = -speed_mid * sin_h * dt
    F[N, HEADING] = speed_mid * cos_h * dt
    F[E, SPEED] = cos_h * dt
    F[N, SPEED] = sin_h * dt
    F[E, ACCEL] = 0.5 * cos_h * dt * dt
    F[N, ACCEL] = 0.5 * sin_h * dt * dt


class CtraModel:
    kind = MotionModelKind.CTRA

    def __init__(self, noise: ProcessNoise) -> None:
        self.noise = noise
        self._q_by_dt: dict[float, np.ndarray] = {}  # inputs come at a few fixed rates

    def step(self, x: np.ndarray, dt: float, steering_angle_rad: float = 0.0
             ) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        """The steering angle does not enter CTRA: its yaw rate is a state of its own."""
        F = np.eye(STATE_DIM)
        x_new = x.copy()
        _position_step(x, x[YAW_RATE], dt, F, x_new)
        # The mid-step heading moves by yaw_rate * dt / 2.
        F[E, YAW_RATE] = F[E, HEADING] * 0.5 * dt
        F[N, YAW_RATE] = F[N, HEADING] * 0.5 * dt
        x_new[HEADING] = x[HEADING] + x[YAW_RATE] * dt
        F[HEADING, YAW_RATE] = dt
        x_new[SPEED] = x[SPEED] + x[ACCEL] * dt
        F[SPEED, ACCEL] = dt
        _gnss_error_step(self.noise, x, dt, F, x_new)
        return x_new, F, self.process_noise(dt)

    def process_noise(self, dt: float) -> np.ndarray:
        cached = self._q_by_dt.get(dt)
        if cached is not None:
            return cached
        Q = np.zeros((STATE_DIM, STATE_DIM))
        Q[E, E] = Q[N, N] = self.noise.position_std_mps**2 * dt
        _set_integrated_pair(Q, HEADING, YAW_RATE, self.noise.yaw_accel_std_radps2**2, dt)
        _set_integrated_pair(Q, SPEED, ACCEL, self.noise.jerk_std_mps3**2, dt)
        _add_bias_walk(Q, self.noise, dt)
        if len(self._q_by_dt) < MAX_CACHED_STEPS:
            self._q_by_dt[dt] = Q
        return Q


class KinematicBicycleModel:
    """Yaw rate follows the steering input; the yaw-rate state is kept equal to v tan(delta) / L."""

    kind = MotionModelKind.KINEMATIC_BICYCLE

    def __init__(self, noise: ProcessNoise, wheelbase_m: float) -> None:
        if wheelbase_m <= 0.0:
            raise ValueError(f"wheelbase_m must be positive, got {wheelbase_m}")
        self.noise = noise
        self.wheelbase_m = wheelbase_m

    def step(self, x: np.ndarray, dt: float, steering_angle_rad: float = 0.0
             ) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        tan_delta = math.tan(steering_angle_rad)
        yaw_rate = x[SPEED] * tan_delta / self.wheelbase_m
        F = np.zeros((STATE_DIM, STATE_DIM))
        np.fill_diagonal(F, 1.0)
        x_new = x.copy()
        _position_step(x, yaw_rate, dt, F, x_new)
        # Position depends on v also through the yaw rate at mid-step.
        d_yaw_rate_dv = tan_delta / self.wheelbase_m
        F[E, SPEED] += F[E, HEADING] * 0.5 * dt * d_yaw_rate_dv
        F[N, SPEED] += F[N, HEADING] * 0.5 * dt * d_yaw_rate_dv
        x_new[HEADING] = x[HEADING] + yaw_rate * dt
        F[HEADING, SPEED] = d_yaw_rate_dv * dt
        x_new[SPEED] = x[SPEED] + x[ACCEL] * dt
        F[SPEED, ACCEL] = dt
        x_new[YAW_RATE] = (x[SPEED] + x[ACCEL] * dt) * d_yaw_rate_dv
        F[YAW_RATE, YAW_RATE] = 0.0
        F[YAW_RATE, SPEED] = d_yaw_rate_dv
        F[YAW_RATE, ACCEL] = d_yaw_rate_dv * dt
        _gnss_error_step(self.noise, x, dt, F, x_new)
        return x_new, F, self.process_noise(x, dt, steering_angle_rad)

    def process_noise(self, x: np.ndarray, dt: float, steering_angle_rad: float) -> np.ndarray:
        Q = np.zeros((STATE_DIM, STATE_DIM))
        Q[E, E] = Q[N, N] = self.noise.position_std_mps**2 * dt
        # Steering noise seen as yaw-rate noise: d(yaw_rate)/d(delta) = v / (L cos^2 delta).
        gain = x[SPEED] / (self.wheelbase_m * math.cos(steering_angle_rad) ** 2)
        yaw_rate_var = (gain * self.noise.steering_std_rad) ** 2
        Q[HEADING, HEADING] = yaw_rate_var * dt * dt + self.noise.yaw_accel_std_radps2**2 * dt**3 / 3.0
        Q[YAW_RATE, YAW_RATE] = yaw_rate_var
        _set_integrated_pair(Q, SPEED, ACCEL, self.noise.jerk_std_mps3**2, dt)
        _add_bias_walk(Q, self.noise, dt)
        return Q


MotionModel = CtraModel | KinematicBicycleModel
