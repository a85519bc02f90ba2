"""FollowJudge: a follow run passes only without collision, above standstill, and actually following."""

from coopdrive.services.sim.follow_judge import FollowJudge


def judge_steady(gap_for_speed, speed_mps=20.0, duration_s=30.0):
    judge = FollowJudge(standstill_m=6.0, time_gap_s=1.5)
    for tick in range(int(duration_s * 10)):
        judge.observe(tick / 10, "ego", gap_for_speed(speed_mps), speed_mps, speed_mps, 0.0)
    return judge


def test_following_at_the_desired_spacing_passes_with_zero_error():
    judge = judge_steady(lambda v: 6.0 + 1.5 * v)
    assert judge.verdict() == (True, "")
    assert judge.metrics()["spacing_error_m"] == 0.0
    assert judge.metrics()["min_time_gap_s"] == 1.8


def test_staying_far_behind_fails_as_not_following():
    ok, reason = judge_steady(lambda v: 80.0).verdict()
    assert not ok and reason.startswith("not following: mean spacing error 44.00 m")


def test_a_gap_closing_to_zero_is_one_collision():
    judge = FollowJudge(standstill_m=6.0, time_gap_s=1.5)
    for tick, gap in enumerate([10.0, 2.0, -0.5, -0.2, 3.0]):
        judge.observe(tick, "ego", gap, 10.0, 10.0, -3.0)
    assert judge.collisions == 1
    assert judge.verdict() == (False, "1 collision(s)")
    assert judge.metrics()["max_abs_accel_mps2"] == 3.0


def test_a_run_that_ends_before_the_settle_time_is_too_short_to_judge():
    judge = FollowJudge(standstill_m=6.0, time_gap_s=1.5)
    judge.observe(2.0, "ego", gap_m=30.0, speed_mps=15.0, leader_speed_mps=15.0, accel_mps2=0.0)
    ok, reason = judge.verdict()
    assert not ok and reason.startswith("too short to judge")


def test_spacing_and_speed_errors_are_mean_absolute_with_rms_p95_and_the_signed_bias():
    judge = FollowJudge(standstill_m=6.0, time_gap_s=1.5, settle_time_s=0.0)
    for tick, spacing_error_m in enumerate([1.0, -1.0, 1.0, -1.0]):
        judge.observe(tick, "ego", 6.0 + 1.5 * 10.0 + spacing_error_m, 10.0, 10.0 - spacing_error_m, 0.0)
    figures = judge.metrics()
    assert figures["spacing_error_m"] == 1.0 and figures["spacing_error_rms_m"] == 1.0
    assert figures["spacing_error_bias_m"] == 0.0 and figures["spacing_error_p95_m"] == 1.0
    assert figures["speed_error_kmh"] == 3.6 and figures["speed_error_bias_kmh"] == 0.0
