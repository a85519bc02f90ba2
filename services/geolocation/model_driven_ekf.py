"""ModelDrivenEkf: the extended Kalman filter's two steps, computed as filterpy's ExtendedKalmanFilter does.

Prediction (Labbe, "Kalman and Bayesian Filters in Python", ch. 11): the motion model steps the state,
x = f(x, u), and gives its Jacobian F and process noise Q; then P = F P F^T + Q.
Update with a measurement z of model h(x), Jacobian H and noise R:
    y = z - h(x)  (a residual function, so that angles wrap)
    S = H P H^T + R,  K = P H^T S^-1,  x = x + K y
    P = (I - K H) P (I - K H)^T + K R K^T  (Joseph form: stays symmetric and positive with a rounded K)

The operations and their order are filterpy's, so the results are the same to the bit; the tests hold this
class to filterpy's filter on the same sequences. filterpy itself is not imported: loading it loads scipy.stats,
about a quarter of a vehicle stack's start-up, and it copies its state on every step for read-only properties
(prior, posterior, likelihood) the geolocator never reads.
"""

from __future__ import annotations

from typing import Callable

import numpy as np
import scipy.linalg

from coopdrive.services.geolocation.motion_models import STATE_DIM, MotionModel

Residual = Callable[[np.ndarray, np.ndarray], np.ndarray]


def inverse(S: np.ndarray) -> np.ndarray:
    """scipy.linalg.inv(S). For one row LAPACK's inverse is 1/s, the same bits (tests/geolocation), without the
    checks that cost scipy's call ten times the division: the inertial unit's and a speed's updates are one row."""
    return 1.0 / S if S.shape == (1, 1) else scipy.linalg.inv(S)


class ModelDrivenEkf:
    def __init__(self, model: MotionModel) -> None:
        self.model = model
        self.x = np.zeros(STATE_DIM)
        self.P = np.eye(STATE_DIM)
        self._identity = np.eye(STATE_DIM)

    def predict(self, dt_s: float, steering_angle_rad: float) -> None:
        """One step of the motion model; the caller wraps angles in the new state."""
        self.x, F, Q = self.model.step(self.x, dt_s, steering_angle_rad)
        self.P = np.dot(F, self.P).dot(F.T) + Q

    def update(self, z: np.ndarray, H: np.ndarray, hx: np.ndarray, R: np.ndarray, residual: Residual) -> None:
        """H and h(x) are taken at the state the update starts from."""
        PHT = np.dot(self.P, H.T)
        S = np.dot(H, PHT) + R
        K = PHT.dot(inverse(S))
        self.x = self.x + np.dot(K, residual(z, hx))
        I_KH = self._identity - np.dot(K, H)
        self.P = np.dot(I_KH, self.P).dot(I_KH.T) + np.dot(K, R).dot(K.T)
