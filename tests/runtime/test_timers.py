"""Time triggers fire at their period on whichever clock drives them."""

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


def test_the_next_due_time_is_known_once_every_trigger_has_fired():
    triggers = TriggerSet()
    triggers.add(0.1, lambda now: None)
    triggers.add(0.04, lambda now: None)
    assert triggers.next_due_s() is None
    triggers.run_due(0.0)
    assert triggers.next_due_s() == 0.04
