"""Stepper: a lockstep step of one service, for a follower the barrier released and for the clock master alike.

It runs the step (the messages the step dispatcher holds for it, then the due triggers), holds back what the step
publishes and sends it with the step's marker, and numbers the master's clocks. The StepDone marker rides as the
attachment of the step's last message on each stepped topic (its own @step key for a topic the step left quiet);
it counts the messages it covers, so a follower also waits for any still on their way."""

from __future__ import annotations

import math
from typing import Callable

from google.protobuf.message import Message

from coopdrive.bus import Bus, Envelope
from coopdrive.bus.keys import WORLD_ID
from coopdrive.bus.topics import stepped_topics_of
from coopdrive.runtime.barrier import StepBarrier
from coopdrive.runtime.dispatcher import TIME_EPSILON_S, StepDispatcher
from coopdrive.runtime.service import SequenceCounter
from coopdrive.runtime.timers import TriggerSet
from coopdrive.v1 import sim_pb2


class Stepper:
    def __init__(self, service_name: str, vehicle_id: str, bus: Bus, clock, triggers: TriggerSet,
                 dispatch: Callable[[Envelope], None]):
        """`clock`: the service's clock (set to each step's time). `dispatch`: hands a message to its handlers."""
        self.service_name = service_name
        self.vehicle_id = vehicle_id
        self.bus = bus
        self.clock = clock
        self.triggers = triggers
        self._dispatch = dispatch
        self.sequence = SequenceCounter(service_name)
        self.dispatcher = StepDispatcher(service_name, vehicle_id)
        self.barrier = StepBarrier(service_name)
        # Lockstep: what a step publishes, held back until its marker can go with it (publish_step_done).
        self._outbox: list[tuple[str, str, Message]] | None = None
        self._stepped_topics = frozenset(stepped_topics_of(service_name))
        # The last step marker sent, re-sent to a participant that joins mid-run.
        self._last_marker: sim_pb2.StepDone | None = None
        self.last_step = -1
        self.step_s = 0.0

    def send(self, vehicle_id: str, topic: str, message: Message) -> None:
        """A stamped message: out at once, or with the marker of the step being handled."""
        if self._outbox is not None:
            self._outbox.append((vehicle_id, topic, message))
        else:
            self.bus.publish(vehicle_id, topic, message)

    def note_received(self, envelope: Envelope) -> None:
        self.barrier.mark_received(f"{envelope.vehicle_id}/{envelope.topic}", envelope.message.header.sequence)

    @property
    def published_sequences(self) -> dict[str, int]:
        return dict(self.sequence.last)

    def run_step(self, step: int, time_s: float) -> None:
        self.clock.set(time_s)
        for envelope in self.dispatcher.eligible(time_s):
            self._dispatch(envelope)
        self.triggers.run_due(time_s)
        self.last_step = step

    def run_lockstep_step(self, step: int, time_s: float) -> None:
        """Handles a released step, then sends what it published together with its step marker."""
        self._outbox = []
        self.run_step(step, time_s)
        self.publish_step_done(step)

    def publish_step_done(self, step: int) -> None:
        """Sends the step's messages and tells every subscriber of each stepped topic that the step is done.

        The marker rides as the attachment of the step's last message on each topic, so a step costs no
        extra message on the topics it used; a topic left quiet gets the marker on its own @step key.
        """
        marker = sim_pb2.StepDone(step=step, service=self.service_name, next_step=self._next_active_step(step),
                                  sequences=self.sequence.last)
        marker.header.sent_time_s = self.clock.now_s()
        marker.header.vehicle_id = self.vehicle_id
        marker.header.sender = self.service_name
        attachment = marker.SerializeToString()
        self._last_marker = marker
        outbox, self._outbox = self._outbox or [], None
        last_of_topic = {(vehicle_id, topic): index for index, (vehicle_id, topic, _) in enumerate(outbox)}
        for index, (vehicle_id, topic, message) in enumerate(outbox):
            carries_marker = (vehicle_id == self.vehicle_id and topic in self._stepped_topics
                              and last_of_topic[(vehicle_id, topic)] == index)
            self.bus.publish(vehicle_id, topic, message, attachment=attachment if carries_marker else None)
        sent = {topic for vehicle_id, topic, _ in outbox if vehicle_id == self.vehicle_id}
        for topic in self._stepped_topics:
            if topic not in sent:
                self.bus.put_if_subscribed(self.bus.layout.step_done(self.vehicle_id, topic), marker)

    def resend_last_marker(self) -> None:
        if self._last_marker is not None:
            for topic in self._stepped_topics:
                self.bus.put_if_subscribed(self.bus.layout.step_done(self.vehicle_id, topic), self._last_marker)

    def publish_clock(self, clock: sim_pb2.SimClock, followers_key: str) -> None:
        """The clock master's clock: numbered as world/clock and sent to the followers on `followers_key`
        (KeyLayout.clock_step or clock_to_all), and on world/clock itself for whoever records or shows it."""
        self.sequence.stamp(clock, WORLD_ID, "clock", self.clock.now_s(), None)
        self.bus.put(followers_key, clock)
        self.bus.put_if_subscribed(self.bus.layout.topic(WORLD_ID, "clock"), clock)

    def _next_active_step(self, step: int) -> int:
        next_due = self.triggers.next_due_s()
        if next_due is None or self.step_s <= 0:
            return step + 1
        return max(step + 1, math.ceil(next_due / self.step_s - TIME_EPSILON_S * 1e3))
