import math

import numpy as np
import pytest
from hypothesis import assume, given, settings
from hypothesis import strategies as st

from coopdrive.services.scene.association import (
    DENSE_PAIRS_MAX,
    assign,
    gate_groups,
    likelihood_cost,
    match_quality,
    polar_cost_loop,
    polar_cost_matrix,
    polar_cost_pairs,
)
from coopdrive.services.scene.config import TrackingConfig
from coopdrive.services.scene.frame_association import ONE_MATRIX_MAX, associate, associate_confirmed_first

ORIGIN = np.zeros(2)


def costs(meas_xy, track_xy, std_m=0.5, emphasis=1.0):
    meas_xy, track_xy = np.asarray(meas_xy, float), np.asarray(track_xy, float)
    meas_cov = np.repeat(np.eye(2)[None] * std_m**2, len(meas_xy), axis=0)
    track_cov = np.repeat(np.eye(2)[None] * std_m**2, len(track_xy), axis=0)
    origins = np.zeros_like(meas_xy)
    return polar_cost_matrix(meas_xy, meas_cov, origins, track_xy, track_cov, emphasis)


def test_assignment_picks_the_global_optimum_where_greedy_nearest_neighbour_would_not():
    # Greedy takes the cheapest pair (m0, t0) = 1 first and is left with (m1, t1) = 100: total 101.
    # The optimum pairs (m0, t1) + (m1, t0) = 5 + 5 = 10.
    cost = np.array([[1.0, 5.0], [5.0, 100.0]])
    pairs, unmatched = assign(cost, gate=1000.0)
    assert sorted(pairs) == [(0, 1), (1, 0)]
    assert unmatched == []


def test_pairs_outside_the_gate_are_never_assigned_and_their_measurements_start_tracks():
    cost = np.array([[1.0, 50.0], [50.0, 40.0]])
    pairs, unmatched = assign(cost, gate=9.21)
    assert pairs == [(0, 0)]
    assert unmatched == [1]


def test_the_gate_is_a_mahalanobis_distance_in_range_and_bearing():
    # 1 m further away at 20 m with 0.5 m std on both: range residual 1 over variance 0.5.
    (cost,) = costs([[21.0, 0.0]], [[20.0, 0.0]])
    assert cost[0] == pytest.approx(1.0 / 0.5, rel=1e-6)


def test_the_bearing_residual_weighs_more_than_the_range_residual_by_the_angle_emphasis():
    along = costs([[21.0, 0.0]], [[20.0, 0.0]], emphasis=1.2)[0, 0]
    across = costs([[20.0, 1.0]], [[20.0, 0.0]], emphasis=1.2)[0, 0]
    assert across > along


def test_match_quality_is_one_for_a_perfect_match_and_one_half_at_the_gate():
    assert match_quality(0.0, 9.21) == 1.0
    assert match_quality(9.21, 9.21) == pytest.approx(0.5)
    assert match_quality(50.0, 9.21) == pytest.approx(0.5)


def test_an_empty_frame_or_empty_track_list_assigns_nothing():
    assert assign(np.zeros((0, 3)), 9.21) == ([], [])
    assert assign(np.zeros((2, 0)), 9.21) == ([], [0, 1])


coordinate = st.floats(min_value=-60.0, max_value=60.0, allow_nan=False)


@settings(max_examples=40, deadline=None, derandomize=True)
@given(st.lists(st.tuples(coordinate, coordinate), min_size=1, max_size=5),
       st.lists(st.tuples(coordinate, coordinate), min_size=1, max_size=5))
def test_the_vectorised_cost_matrix_equals_the_pair_by_pair_baseline(meas, tracks):
    meas_xy = np.array(meas) + 0.5  # keep off the sensor origin itself
    track_xy = np.array(tracks) + 0.5
    meas_cov = np.repeat(np.diag([0.3, 0.2])[None], len(meas_xy), axis=0)
    track_cov = np.repeat(np.array([[0.4, 0.1], [0.1, 0.3]])[None], len(track_xy), axis=0)
    origins = np.zeros_like(meas_xy)
    fast = polar_cost_matrix(meas_xy, meas_cov, origins, track_xy, track_cov, 1.2)
    slow = polar_cost_loop(meas_xy, meas_cov, origins, track_xy, track_cov, 1.2)
    assert np.allclose(fast, slow, rtol=1e-6, atol=1e-9)


def test_bearing_residuals_wrap_around_behind_the_sensor():
    (cost,) = costs([[-20.0, 0.01]], [[-20.0, -0.01]])
    assert cost[0] < 1.0
    assert math.isfinite(cost[0])


def test_a_vague_new_track_does_not_outbid_a_sharp_established_track_for_a_measurement():
    meas_xy = np.array([[20.0, 0.2]])
    meas_cov = np.eye(2)[None] * 0.05
    track_xy = np.array([[20.0, 0.0], [20.5, 0.5]])  # sharp, vague
    track_cov = np.stack((np.eye(2) * 0.05, np.eye(2) * 4.0))
    d2, log_det = polar_cost_matrix(meas_xy, meas_cov, np.zeros((1, 2)), track_xy, track_cov, 1.2, with_log_det=True)
    assert d2[0, 1] < d2[0, 0]  # by distance alone the vague track looks closer
    pairs, _ = assign(likelihood_cost(d2, log_det), 9.21, gate_cost=d2)
    assert pairs == [(0, 0)]


GATE = 9.21


def joint_pairs(meas_xy, meas_cov, track_xy, track_cov):
    origins = np.zeros_like(meas_xy)
    d2, log_det = polar_cost_matrix(meas_xy, meas_cov, origins, track_xy, track_cov, 1.2, with_log_det=True)
    return set(assign(likelihood_cost(d2, log_det), GATE, gate_cost=d2)[0])


def grouped_pairs(meas_xy, meas_cov, track_xy, track_cov):
    pairs = set()
    origins = np.zeros_like(meas_xy)
    for group_meas, group_tracks in gate_groups(meas_xy, meas_cov, origins, track_xy, track_cov, GATE, 1.2,
                                                dense_pairs_max=0):
        if group_tracks.size:
            found = joint_pairs(meas_xy[group_meas], meas_cov[group_meas], track_xy[group_tracks],
                                track_cov[group_tracks])
            pairs |= {(int(group_meas[i]), int(group_tracks[j])) for i, j in found}
    return pairs


def traffic(seed, tracks, clutter):
    """Cars in traffic (some close together), most seen again with noise, plus clutter readings: measurement
    positions and covariances, track positions and covariances."""
    rng = np.random.default_rng(seed)
    track_xy = rng.uniform([-60.0, -10.0], [60.0, 10.0], (tracks, 2))
    track_cov = np.einsum("k,ij->kij", rng.uniform(0.01, 4.0, tracks), np.eye(2))
    seen = track_xy[rng.random(tracks) < 0.8]
    meas_xy = np.vstack([seen + rng.normal(0.0, 0.5, seen.shape), rng.uniform([-60.0, -10.0], [60.0, 10.0],
                                                                               (clutter, 2))])
    meas_cov = np.einsum("k,ij->kij", rng.uniform(0.01, 1.0, len(meas_xy)), np.eye(2))
    return meas_xy, meas_cov, track_xy, track_cov


@settings(max_examples=60, deadline=None)
@given(st.integers(0, 2**32 - 1), st.integers(1, 40), st.integers(0, 40))
def test_assigning_gate_groups_one_by_one_gives_the_pairs_of_one_joint_assignment(seed, tracks, clutter):
    meas_xy, meas_cov, track_xy, track_cov = traffic(seed, tracks, clutter)
    if len(meas_xy) == 0:
        return
    assert grouped_pairs(meas_xy, meas_cov, track_xy, track_cov) == joint_pairs(meas_xy, meas_cov, track_xy,
                                                                                track_cov)


def test_far_apart_objects_fall_into_groups_of_their_own():
    track_xy = np.array([[10.0, 0.0], [50.0, 0.0], [90.0, 3.5]])
    meas_xy = track_xy + 0.1
    cov = np.repeat(np.eye(2)[None] * 0.04, 3, axis=0)
    groups = gate_groups(meas_xy, cov, np.zeros_like(meas_xy), track_xy, cov, GATE, 1.2, dense_pairs_max=0)
    assert sorted((g[0].tolist(), g[1].tolist()) for g in groups) == [([0], [0]), ([1], [1]), ([2], [2])]


def test_a_few_objects_make_one_group_since_one_small_matrix_is_cheaper():
    xy = np.array([[10.0, 0.0], [50.0, 0.0]])
    cov = np.repeat(np.eye(2)[None] * 0.04, 2, axis=0)
    [(measurements, tracks)] = gate_groups(xy, cov, np.zeros_like(xy), xy, cov, GATE, 1.2)
    assert measurements.tolist() == [0, 1] and tracks.tolist() == [0, 1]


def test_the_costs_of_given_pairs_are_the_matching_entries_of_the_cost_matrix():
    rng = np.random.default_rng(7)
    meas_xy, track_xy = rng.uniform(-30.0, 30.0, (12, 2)), rng.uniform(-30.0, 30.0, (12, 2))
    meas_cov = np.einsum("k,ij->kij", rng.uniform(0.01, 1.0, 12), np.eye(2))
    track_cov = np.einsum("k,ij->kij", rng.uniform(0.01, 1.0, 12), np.eye(2))
    origins = rng.uniform(-2.0, 2.0, (12, 2))
    d2, log_det = polar_cost_matrix(meas_xy, meas_cov, origins, track_xy, track_cov, 1.2, with_log_det=True)
    pair_d2, pair_log_det = polar_cost_pairs(meas_xy, meas_cov, origins, track_xy, track_cov, 1.2)
    # polar_cost_matrix measures each track from the measurement's origin: the diagonal pairs are the same.
    assert pair_d2 == pytest.approx(np.diag(d2)) and pair_log_det == pytest.approx(np.diag(log_det))


@settings(max_examples=40, deadline=None)
@given(st.integers(0, 2**32 - 1), st.integers(1, 40), st.integers(0, 40),
       st.sampled_from([(0, 0), (0, 30), (0, ONE_MATRIX_MAX), (DENSE_PAIRS_MAX, ONE_MATRIX_MAX)]))
def test_a_frames_association_gives_the_pairs_of_one_joint_assignment(seed, tracks, clutter, limits):
    meas_xy, meas_cov, track_xy, track_cov = traffic(seed, tracks, clutter)
    if len(meas_xy) == 0:
        return
    tracking = TrackingConfig(gate_chi2=GATE, angle_emphasis=1.2)
    matches, unmatched = associate(meas_xy, meas_cov, np.zeros_like(meas_xy), track_xy, track_cov, tracking, None,
                                   *limits)
    expected = joint_pairs(meas_xy, meas_cov, track_xy, track_cov)
    assert {(i, j) for i, j, _ in matches} == expected
    assert sorted(unmatched) == sorted(set(range(len(meas_xy))) - {i for i, _ in expected})


@st.composite
def frames(draw):
    """A seed and a non-empty frame of traffic() drawn from it."""
    seed = draw(st.integers(0, 2**32 - 1))
    frame = traffic(seed, draw(st.integers(1, 30)), draw(st.integers(0, 30)))
    assume(len(frame[0]) > 0)
    return seed, frame


@settings(max_examples=40, deadline=None)
@given(frames())
def test_confirmed_tracks_choose_first_and_tentative_ones_share_out_what_they_leave(seeded_frame):
    seed, (meas_xy, meas_cov, track_xy, track_cov) = seeded_frame
    confirmed = np.random.default_rng(seed).random(len(track_xy)) < 0.5
    tracking = TrackingConfig(gate_chi2=GATE, angle_emphasis=1.2)
    matches, unmatched = associate_confirmed_first(meas_xy, meas_cov, np.zeros_like(meas_xy), track_xy, track_cov,
                                                   confirmed, tracking)
    first = np.flatnonzero(confirmed)
    to_confirmed = {(i, int(first[j])) for i, j in joint_pairs(meas_xy, meas_cov, track_xy[first], track_cov[first])}
    assert {(i, j) for i, j, _ in matches if confirmed[j]} == to_confirmed
    left = sorted(set(range(len(meas_xy))) - {i for i, _ in to_confirmed})
    rest = np.flatnonzero(~confirmed)
    to_tentative = {(left[i], int(rest[j])) for i, j in joint_pairs(meas_xy[left], meas_cov[left], track_xy[rest],
                                                                    track_cov[rest])} if left and rest.size else set()
    assert {(i, j) for i, j, _ in matches if not confirmed[j]} == to_tentative
    assert sorted(unmatched) == sorted(set(left) - {i for i, _ in to_tentative})


@settings(max_examples=30, deadline=None)
@given(frames(), st.sampled_from([(0, 0), (0, ONE_MATRIX_MAX), (DENSE_PAIRS_MAX, ONE_MATRIX_MAX)]))
def test_pairs_the_pair_terms_forbid_are_never_matched_by_any_path_of_the_association(seeded_frame, limits):
    seed, (meas_xy, meas_cov, track_xy, track_cov) = seeded_frame
    forbidden = np.random.default_rng(seed).random((len(meas_xy), len(track_xy))) < 0.3

    def terms(meas_of, track_of):
        return np.zeros(meas_of.size), ~forbidden[meas_of, track_of]

    tracking = TrackingConfig(gate_chi2=GATE, angle_emphasis=1.2)
    matches, _ = associate(meas_xy, meas_cov, np.zeros_like(meas_xy), track_xy, track_cov, tracking, terms, *limits)
    d2, log_det = polar_cost_matrix(meas_xy, meas_cov, np.zeros_like(meas_xy), track_xy, track_cov, 1.2,
                                    with_log_det=True)
    expected, _ = assign(likelihood_cost(d2, log_det), GATE, gate_cost=np.where(forbidden, np.inf, d2))
    assert {(i, j) for i, j, _ in matches} == set(expected)
