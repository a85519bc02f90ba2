"""The NEES chi-square test of coopdrive/judging/consistency.py against scipy's chi-square distribution and
Bar-Shalom's worked figures; no run needed."""

import math

import numpy as np
import pytest
from scipy.stats import chi2

from coopdrive.judging.consistency import (CONSISTENT_TWO_SIGMA_SHARE, consistency_figures, decimated,
                                           mean_nees_bounds, nees)


@pytest.mark.parametrize("samples", [1, 6, 60, 1000])
def test_the_average_nees_bounds_are_the_chi_square_quantiles_of_n_times_the_dimension_over_n(samples):
    lower, upper = mean_nees_bounds(samples, 2)
    assert lower == pytest.approx(chi2.ppf(0.025, 2 * samples) / samples)
    assert upper == pytest.approx(chi2.ppf(0.975, 2 * samples) / samples)


def test_bar_shalom_s_example_of_50_runs_of_a_2_d_state_gives_1_6_to_2_5():
    # Bar-Shalom, Li and Kirubarajan 5.4.2: N = 50 runs, n = 2: [74.2, 129.6] / 50.
    lower, upper = mean_nees_bounds(50, 2)
    assert (lower, upper) == pytest.approx((1.5, 2.6), abs=0.02)


def test_no_samples_give_no_bounds_rather_than_a_division_by_zero():
    assert all(math.isnan(bound) for bound in mean_nees_bounds(0, 2))


def test_samples_of_a_consistent_2_d_estimate_have_nees_2_and_86_5_percent_inside_the_2_sigma_ellipse():
    rng = np.random.default_rng(4)
    covariance = np.array([[0.04, 0.01], [0.01, 0.09]])
    errors = rng.multivariate_normal([0.0, 0.0], covariance, size=200_000)
    values = nees(errors, np.broadcast_to(covariance, (len(errors), 2, 2)))
    assert np.mean(values) == pytest.approx(2.0, abs=0.02)
    assert np.mean(values <= 4.0) == pytest.approx(CONSISTENT_TWO_SIGMA_SHARE, abs=0.005)
    assert CONSISTENT_TWO_SIGMA_SHARE == pytest.approx(0.8647, abs=1e-4)


def test_decimation_keeps_one_sample_a_second_from_the_first():
    time_s = np.arange(0.0, 3.5, 0.02)
    assert list(time_s[decimated(time_s)]) == pytest.approx([0.0, 1.0, 2.0, 3.0])


def test_an_overconfident_estimate_lies_above_its_upper_bound_and_the_figures_say_so():
    rng = np.random.default_rng(1)
    errors = rng.normal(0.0, 0.3, (60, 2))  # covariance claims 0.1 m: NEES about 18
    values = nees(errors, np.broadcast_to(np.eye(2) * 0.01, (60, 2, 2)))
    figures = consistency_figures(values, values, 2, "position")
    assert figures["position_nees_mean_1hz"] > figures["position_nees_upper_95"]
    assert figures["position_2sigma_share"] < 0.5
