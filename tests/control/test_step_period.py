"""The controllers' step period: the time since the last call, the control period for the first call, and a break
(a gap over MAX_DT_S or time going backwards) told apart so the longitudinal controller can start again."""

from coopdrive.services.control.step_period import DEFAULT_DT_S, MAX_DT_S, step_period_s


def test_the_first_call_takes_the_control_period_and_is_no_break():
    assert step_period_s(None, 12.0) == (DEFAULT_DT_S, False)


def test_a_call_within_the_limit_takes_the_time_since_the_last():
    assert step_period_s(10.0, 10.05) == (10.05 - 10.0, False)
    assert step_period_s(10.0, 10.0 + MAX_DT_S) == (MAX_DT_S, False)


def test_a_gap_over_the_limit_a_repeated_time_and_time_going_backwards_are_breaks():
    for time_s in (10.0 + MAX_DT_S + 0.01, 10.0, 9.9):
        assert step_period_s(10.0, time_s) == (DEFAULT_DT_S, True)
