from coopdrive.services.geolocation.latency import Insertion, ReplayBuffer


class Recorder:
    """A 'filter' whose state is the list of events it has seen, in order."""

    def __init__(self):
        self.seen: tuple = ()

    def apply(self, time_s, event):
        self.seen = self.seen + ((time_s, event),)


def buffer_for(recorder: Recorder, horizon_s: float = 1.0) -> ReplayBuffer:
    return ReplayBuffer(recorder.apply, lambda: recorder.seen, lambda s: setattr(recorder, "seen", s), horizon_s)


def test_in_order_events_are_applied_once():
    recorder = Recorder()
    buffer = buffer_for(recorder)
    for t in (0.0, 0.1, 0.2):
        assert buffer.add(t, f"odo{t}") is Insertion.IN_ORDER
    assert [event for _, event in recorder.seen] == ["odo0.0", "odo0.1", "odo0.2"]


def test_a_late_event_is_applied_at_its_time_and_later_events_are_replayed_after_it():
    recorder = Recorder()
    buffer = buffer_for(recorder)
    for t in (0.0, 0.1, 0.2, 0.3):
        buffer.add(t, "odo")
    assert buffer.add(0.15, "fix") is Insertion.REPLAYED
    assert recorder.seen == ((0.0, "odo"), (0.1, "odo"), (0.15, "fix"), (0.2, "odo"), (0.3, "odo"))
    assert buffer.replayed_events == 2


def test_an_event_older_than_the_history_is_refused_and_counted():
    recorder = Recorder()
    buffer = buffer_for(recorder, horizon_s=0.25)
    for t in (0.0, 0.1, 0.2, 0.3, 0.4):
        buffer.add(t, "odo")
    assert buffer.add(0.05, "fix") is Insertion.TOO_OLD
    assert buffer.counts[Insertion.TOO_OLD] == 1
    assert all(event == "odo" for _, event in recorder.seen)
