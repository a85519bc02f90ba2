"""StepDispatcher: what a service handles in a lockstep step, and in which order."""

from coopdrive.bus import Envelope
from coopdrive.runtime.dispatcher import StepDispatcher
from coopdrive.v1 import control_pb2, ego_pb2, sim_pb2


def envelope(topic, message, sender, sent_time_s, sequence=1, vehicle="ego"):
    message.header.sender = sender
    message.header.sent_time_s = sent_time_s
    message.header.sequence = sequence
    return Envelope(vehicle, topic, message)


def test_upstream_messages_of_the_same_step_are_handled_in_that_step():
    dispatcher = StepDispatcher("control", "ego")
    dispatcher.add(envelope("ego/state", ego_pb2.EgoState(), "geolocation", 0.02))
    assert [e.topic for e in dispatcher.eligible(0.02)] == ["ego/state"]


def test_feedback_from_downstream_waits_for_the_next_step():
    dispatcher = StepDispatcher("geolocation", "ego")
    dispatcher.add(envelope("control/command", control_pb2.ControlCommand(), "control", 0.02))
    assert dispatcher.eligible(0.02) == []
    assert [e.topic for e in dispatcher.eligible(0.03)] == ["control/command"]


def test_messages_from_later_steps_are_held_back():
    dispatcher = StepDispatcher("control", "ego")
    dispatcher.add(envelope("ego/state", ego_pb2.EgoState(), "geolocation", 0.05))
    assert dispatcher.eligible(0.04) == []
    assert len(dispatcher) == 1


def test_order_follows_send_time_then_pipeline_rank_not_arrival():
    dispatcher = StepDispatcher("control", "ego")
    dispatcher.add(envelope("planner/behaviour", sim_pb2.SimClock(), "planner", 0.02))
    dispatcher.add(envelope("ego/state", ego_pb2.EgoState(), "geolocation", 0.02))
    dispatcher.add(envelope("ego/state", ego_pb2.EgoState(), "geolocation", 0.01, sequence=0))
    handled = [(e.message.header.sent_time_s, e.message.header.sender) for e in dispatcher.eligible(0.02)]
    assert handled == [(0.01, "geolocation"), (0.02, "geolocation"), (0.02, "planner")]


def test_a_service_that_joins_mid_run_handles_nothing_sent_before_its_first_step():
    dispatcher = StepDispatcher("control", "ego")
    dispatcher.add(envelope("ego/state", ego_pb2.EgoState(), "geolocation", 6.98))
    dispatcher.start_at(7.0)
    dispatcher.add(envelope("ego/state", ego_pb2.EgoState(), "geolocation", 6.99, sequence=2))
    dispatcher.add(envelope("ego/state", ego_pb2.EgoState(), "geolocation", 7.0, sequence=3))
    assert [e.message.header.sequence for e in dispatcher.eligible(7.0)] == [3]
