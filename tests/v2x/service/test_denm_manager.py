import pytest

from coopdrive.services.v2x.denm_manager import ActionId, DenmManager, UnknownActionError
from coopdrive.v1 import its_pb2

from .streams import CLOCK

STEP_S = 0.01


def road_works(speed_limit_mps: float = 8.3) -> its_pb2.DenmContent:
    event = its_pb2.DenmContent(validity_duration_s=10.0,
                                relevance_distance=its_pb2.RELEVANCE_DISTANCE_LESS_THAN_500M)
    event.event_position.latitude_deg, event.event_position.longitude_deg = 51.45, 5.48
    event.situation.event_type.cause_code = 3
    event.alacarte.road_works.speed_limit_mps = speed_limit_mps
    return event


def run(manager: DenmManager, start_s: float, end_s: float) -> list[tuple[float, its_pb2.DenmContent]]:
    sent = []
    for step in range(round(start_s / STEP_S), round(end_s / STEP_S)):
        now_s = step * STEP_S
        sent += [(now_s, content) for content in manager.due(now_s, CLOCK.tai_ms(now_s))]
    return sent


def rsu() -> DenmManager:
    return DenmManager(station_id=99, station_type=its_pb2.STATION_TYPE_ROAD_SIDE_UNIT, protocol_version=1)


def test_a_triggered_denm_is_sent_at_once_and_repeated_at_its_interval_with_one_action_id():
    manager = rsu()
    action = manager.trigger(road_works(), 0.0, CLOCK.tai_ms(0.0), repetition_interval_s=0.04)
    sent = run(manager, 0.0, 1.0)
    assert len(sent) == 25
    assert {(c.originating_station_id, c.sequence_number) for _, c in sent} == {(99, action.sequence_number)}
    first = sent[0][1]
    assert first.detection_time_tai_ms == first.reference_time_tai_ms == CLOCK.tai_ms(0.0)
    assert first.station_type == its_pb2.STATION_TYPE_ROAD_SIDE_UNIT
    assert first.transmission_interval_s == pytest.approx(0.04)


def test_each_new_event_gets_the_next_sequence_number():
    manager = rsu()
    actions = [manager.trigger(road_works(), 0.0, 0) for _ in range(3)]
    assert actions == [ActionId(99, 0), ActionId(99, 1), ActionId(99, 2)]


def test_an_update_keeps_the_action_id_and_detection_time_and_sets_a_new_reference_time():
    manager = rsu()
    action = manager.trigger(road_works(8.3), 0.0, CLOCK.tai_ms(0.0), repetition_interval_s=0.1)
    run(manager, 0.0, 0.5)
    manager.update(action, road_works(5.5), 0.5, CLOCK.tai_ms(0.5))
    now_s, updated = run(manager, 0.5, 0.51)[0]
    assert now_s == 0.5
    assert updated.alacarte.road_works.speed_limit_mps == pytest.approx(5.5)
    assert (updated.originating_station_id, updated.sequence_number) == (99, action.sequence_number)
    assert updated.detection_time_tai_ms == CLOCK.tai_ms(0.0)
    assert updated.reference_time_tai_ms == CLOCK.tai_ms(0.5)


def test_a_cancelled_event_sends_cancellations_for_a_while_then_is_forgotten():
    manager = rsu()
    action = manager.trigger(road_works(), 0.0, CLOCK.tai_ms(0.0), repetition_interval_s=0.1)
    run(manager, 0.0, 1.0)
    manager.cancel(action, 1.0, CLOCK.tai_ms(1.0), repetition_duration_s=0.5)
    sent = run(manager, 1.0, 3.0)
    assert all(c.termination == its_pb2.DENM_TERMINATION_CANCELLATION for _, c in sent)
    assert [t for t, _ in sent] == pytest.approx([1.0, 1.1, 1.2, 1.3, 1.4, 1.5])
    assert manager.active == []
    with pytest.raises(UnknownActionError):
        manager.update(action, road_works(), 3.0, CLOCK.tai_ms(3.0))


def test_an_event_stops_at_the_end_of_its_validity():
    manager = rsu()
    manager.trigger(road_works(), 0.0, CLOCK.tai_ms(0.0), repetition_interval_s=1.0)
    sent = run(manager, 0.0, 15.0)
    assert [t for t, _ in sent] == pytest.approx([float(second) for second in range(11)])
    assert manager.active == []


def test_a_denm_without_repetition_is_sent_once_but_stays_cancellable():
    manager = rsu()
    action = manager.trigger(road_works(), 0.0, CLOCK.tai_ms(0.0))
    assert len(run(manager, 0.0, 2.0)) == 1
    manager.cancel(action, 2.0, CLOCK.tai_ms(2.0), repetition_duration_s=0.0)
    sent = run(manager, 2.0, 3.0)
    assert [c.termination for _, c in sent] == [its_pb2.DENM_TERMINATION_CANCELLATION]
