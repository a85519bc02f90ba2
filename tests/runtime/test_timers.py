"""Time triggers fire at their period on whichever clock drives them."""

import pytest

from coopdrive.runtime.timers import TriggerSet


def test_a_trigger_fires_at_once_then_every_period():
    fired = []
    triggers = TriggerSet()
    triggers.add(0.02, fired.append)
    for step in range(7):
        triggers.run_due(step * 0.01)
    assert fired == [0.0, 0.02, 0.04, 0.06]


def test_missed_periods_are_skipped_not_burst():
    fired = []
    triggers = TriggerSet()
    triggers.add(0.1, fired.append)
    triggers.run_due(0.0)
    triggers.run_due(0.55)
    triggers.run_due(0.58)
    triggers.run_due(0.6)
    assert fired == [0.0, 0.55, 0.6]


def test_missed_periods_are_counted_per_trigger_and_reported_when_they_happen():
    reported = []

    def control(now_s: float) -> None:
        pass

    def status(now_s: float) -> None:
        pass

    triggers = TriggerSet(on_overrun=lambda trigger, missed: reported.append((trigger.name, missed)))
    triggers.add(0.1, control)
    triggers.add(1.0, status)
    for now_s in (0.0, 0.1, 0.45, 0.5, 0.8):
        triggers.run_due(now_s)
    # control was due at 0.2 and 0.3 (ran at 0.45, due again 0.5) and at 0.6 and 0.7 (ran at 0.8)
    assert reported == [("control", 2), ("control", 2)]
    assert triggers.overruns() == {"control": 4, "status": 0}


def test_the_next_due_time_is_known_once_every_trigger_has_fired():
    triggers = TriggerSet()
    triggers.add(0.1, lambda now: None)
    triggers.add(0.04, lambda now: None)
    assert triggers.next_due_s() is None
    triggers.run_due(0.0)
    assert triggers.next_due_s() == 0.04


def failing(now_s: float) -> None:
    raise ZeroDivisionError(f"at {now_s}")


def test_a_failing_handler_is_reported_and_the_other_triggers_and_later_periods_still_run():
    fired, failures = [], []
    triggers = TriggerSet(on_error=lambda trigger, error: failures.append((trigger.handler, str(error))))
    triggers.add(0.02, failing)
    triggers.add(0.02, fired.append)
    for step in range(3):
        triggers.run_due(step * 0.02)
    assert fired == [0.0, 0.02, 0.04]
    assert failures == [(failing, "at 0.0"), (failing, "at 0.02"), (failing, "at 0.04")]


def test_without_an_error_handler_a_failing_handler_raises_so_a_replay_stops_where_it_failed():
    triggers = TriggerSet()
    triggers.add(0.02, failing)
    with pytest.raises(ZeroDivisionError):
        triggers.run_due(0.0)


def test_triggers_started_mid_run_fire_on_their_grid_from_time_zero():
    fired = []
    triggers = TriggerSet()
    triggers.add(0.1, fired.append)
    triggers.start_at(7.02)
    for step in range(700, 722):
        triggers.run_due(step * 0.01)
    assert fired == pytest.approx([7.1, 7.2])
