"""ModelDrivenEkf against filterpy's ExtendedKalmanFilter, driven by the same motion model on the same sequences.

filterpy is the reference here only: the geolocation service does not import it (nor scipy.stats, which it loads).
"""

import subprocess
import sys

import numpy as np
import pytest
import scipy.linalg
from filterpy.kalman import ExtendedKalmanFilter
from hypothesis import given, settings
from hypothesis import strategies as st
from scipy.stats import chi2

from coopdrive.services.geolocation.ekf import chi2_quantile, normalised_innovation_squared
from coopdrive.services.geolocation.model_driven_ekf import ModelDrivenEkf, inverse
from coopdrive.services.geolocation.motion_models import (
    HEADING, SPEED, STATE_DIM, YAW_RATE, CtraModel, KinematicBicycleModel, ProcessNoise,
)


class FilterpyModelDriven(ExtendedKalmanFilter):
    """filterpy's EKF whose prediction steps the motion model (its documented predict_x hook)."""

    def __init__(self, model):
        super().__init__(dim_x=STATE_DIM, dim_z=2)
        self.model = model
        self.x = np.zeros(STATE_DIM)

    def predict_x(self, u):
        dt_s, steering_angle_rad = u
        self.x, self.F, self.Q = self.model.step(self.x, dt_s, steering_angle_rad)


def _measurement(rng, x):
    """A random one- or two-row measurement of the state: position, speed and yaw rate, or a heading."""
    choices = ([0, 1], [SPEED, YAW_RATE], [SPEED], [HEADING])
    rows = choices[rng.integers(len(choices))]
    H = np.zeros((len(rows), STATE_DIM))
    H[range(len(rows)), rows] = 1.0
    hx = x[rows]
    z = hx + rng.normal(0.0, 0.5, len(rows))
    R = np.diag(rng.uniform(0.01, 1.0, len(rows)))
    return z, H, hx, R


@pytest.mark.parametrize("model", [CtraModel(ProcessNoise()), KinematicBicycleModel(ProcessNoise(), 2.7)],
                         ids=["ctra", "kinematic_bicycle"])
@pytest.mark.parametrize("seed", [1, 2, 3])
def test_the_filter_gives_filterpys_state_and_covariance_to_the_bit(model, seed):
    rng = np.random.default_rng(seed)
    ours, reference = ModelDrivenEkf(model), FilterpyModelDriven(model)
    x0 = np.array([10.0, -5.0, 0.3, 20.0, 0.05, 0.5, 0.001, 0.02, 0.3, -0.2, 0.004])
    ours.x, reference.x = x0.copy(), x0.copy()
    ours.P = np.diag(rng.uniform(0.1, 2.0, STATE_DIM))
    reference.P = ours.P.copy()
    for _ in range(300):
        dt_s, steering_angle_rad = float(rng.uniform(0.001, 0.02)), float(rng.normal(0.0, 0.05))
        ours.predict(dt_s, steering_angle_rad)
        reference.predict(u=(dt_s, steering_angle_rad))
        if rng.uniform() < 0.4:
            z, H, hx, R = _measurement(rng, ours.x)
            ours.update(z, H, hx, R, residual=np.subtract)
            reference.update(z, HJacobian=lambda _x, H=H: H, Hx=lambda _x, hx=hx: hx, R=R)
        assert np.array_equal(ours.x, reference.x)
        assert np.array_equal(ours.P, reference.P)


@pytest.mark.parametrize("dof", [1, 2, 3, 4])
@pytest.mark.parametrize("probability", [0.99, 0.999])
def test_the_gate_quantile_is_scipy_stats_chi2_ppf(dof, probability):
    assert chi2_quantile(probability, dof) == chi2.ppf(probability, dof)


def test_the_geolocation_service_imports_neither_filterpy_nor_scipy_stats():
    """filterpy pulls in scipy.stats: about a quarter of the imports of a process that runs a vehicle's stack."""
    code = ("import sys, coopdrive.services.geolocation.service; "
            "print('filterpy' in sys.modules, 'scipy.stats' in sys.modules)")
    output = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, check=True).stdout
    assert output.split() == ["False", "False"]


positive_variances = st.floats(min_value=1e-9, max_value=1e9, allow_nan=False, allow_infinity=False)
residuals = st.floats(min_value=-1e6, max_value=1e6, allow_nan=False, allow_infinity=False)


@settings(max_examples=500, deadline=None)
@given(positive_variances)
def test_a_one_row_innovation_covariance_is_inverted_to_scipys_bits(variance):
    S = np.array([[variance]])
    assert np.array_equal(inverse(S), scipy.linalg.inv(S))


@settings(max_examples=500, deadline=None)
@given(residuals, positive_variances)
def test_a_one_row_normalised_innovation_squared_is_numpys_solve_to_the_bit(residual, variance):
    y, S = np.array([residual]), np.array([[variance]])
    assert normalised_innovation_squared(y, S) == float(y @ np.linalg.solve(S, y))


def test_two_rows_go_through_numpys_solve_and_scipys_inverse():
    y, S = np.array([0.3, -1.2]), np.array([[2.0, 0.4], [0.4, 1.5]])
    assert normalised_innovation_squared(y, S) == float(y @ np.linalg.solve(S, y))
    assert np.array_equal(inverse(S), scipy.linalg.inv(S))
