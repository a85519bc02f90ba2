"""ParticipantTracker: liveliness in simulated time comes from the clock's participant list."""

from coopdrive.runtime.participants import ParticipantTracker


def test_the_first_clock_reports_the_simulator_and_every_participant_alive_in_order():
    tracker = ParticipantTracker()
    assert tracker.update(["ego/scene", "ego/control"]) == [
        ("ego/control", True), ("ego/scene", True), ("world/sim", True)]


def test_an_unchanged_list_reports_nothing_and_a_dropped_participant_is_reported_dead():
    tracker = ParticipantTracker()
    tracker.update(["ego/scene", "ego/control"])
    assert tracker.update(["ego/scene", "ego/control"]) == []
    assert tracker.update(["ego/scene"]) == [("ego/control", False)]
