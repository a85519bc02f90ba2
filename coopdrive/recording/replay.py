"""Replay: feeds one service its recorded inputs, step by step, and collects what it publishes.

The service runs in this process with a ReplayContext instead of a bus. Each recorded
lockstep clock step k is replayed by first handing the dispatcher every recorded input sent up
to that step, then applying the same StepDispatcher rule the live runner used; a
deterministic service therefore publishes exactly what it published live.
"""

from __future__ import annotations

import json
import logging
from collections import defaultdict
from dataclasses import dataclass, field
from pathlib import Path
from typing import Callable

from google.protobuf.message import Message

from coopdrive.bus import Envelope, KeyLayout
from coopdrive.bus.keys import WORLD_ID
from coopdrive.recording.reader import RecordedMessage, read_messages, read_metadata
from coopdrive.recording.writer import McapRecorder
from coopdrive.runtime.clock import SimulationClock
from coopdrive.runtime.dispatcher import TIME_EPSILON_S, StepDispatcher
from coopdrive.runtime.participants import ParticipantTracker
from coopdrive.runtime.registry import service_class
from coopdrive.runtime.service import SequenceCounter
from coopdrive.runtime.timers import TriggerSet


class ReplayError(RuntimeError):
    pass


@dataclass
class ReplayContext:
    """A ServiceContext backed by a recording instead of a bus."""

    vehicle_id: str
    service_name: str
    log: logging.Logger = field(default_factory=lambda: logging.getLogger("coopdrive.replay"))
    clock: SimulationClock = field(default_factory=SimulationClock)
    triggers: TriggerSet = field(default_factory=TriggerSet)
    handlers: dict = field(default_factory=lambda: defaultdict(list))
    outputs: list[tuple[str, Message]] = field(default_factory=list)
    liveliness_handlers: list = field(default_factory=list)
    _sequence: SequenceCounter | None = None
    layout: KeyLayout = field(default_factory=KeyLayout)
    opens_hardware: bool = False

    def now_s(self) -> float:
        return self.clock.now_s()

    def subscribe(self, topic: str, handler: Callable[[Envelope], None], vehicle_id: str | None = None) -> None:
        self.handlers[topic].append((vehicle_id or self.vehicle_id, handler))

    def publish(self, topic: str, message: Message, sample_time_s: float | None = None) -> None:
        self.publish_for(self.vehicle_id, topic, message, sample_time_s)

    def publish_for(self, vehicle_id: str, topic: str, message: Message, sample_time_s: float | None = None) -> None:
        if self._sequence is None:
            self._sequence = SequenceCounter(self.service_name)
        self._sequence.stamp(message, vehicle_id, topic, self.clock.now_s(), sample_time_s)
        self.outputs.append((self.layout.topic(vehicle_id, topic), message))

    def every(self, period_s: float, handler: Callable[[float], None]) -> None:
        self.triggers.add(period_s, handler)

    def watch_liveliness(self, handler: Callable[[str, bool], None]) -> None:
        self.liveliness_handlers.append(handler)

    def call_soon(self, function: Callable[[], None]) -> None:
        function()

    def request_stop(self, reason: str) -> None:
        self.log.info("service asked to stop: %s", reason)


@dataclass
class ReplayResult:
    outputs: list[tuple[str, Message]]
    recorded_outputs: list[tuple[str, Message]]
    steps: int

    def mismatches(self, skip_topics: tuple[str, ...] = ("diagnostics/",)) -> list[str]:
        """Differences between replayed and recorded outputs, in words (empty when equal)."""
        def keep(items):
            return [(t, m) for t, m in items if not any(part in t for part in skip_topics)]

        replayed, recorded = keep(self.outputs), keep(self.recorded_outputs)
        problems = []
        if len(replayed) != len(recorded):
            problems.append(f"{len(replayed)} messages replayed, {len(recorded)} recorded")
        for index, ((t1, m1), (t2, m2)) in enumerate(zip(replayed, recorded)):
            if t1 != t2 or m1.SerializeToString(deterministic=True) != m2.SerializeToString(deterministic=True):
                problems.append(f"message {index} differs: replayed {t1} vs recorded {t2}")
                break
        return problems


def replay_service(recording: str | Path, service_name: str, vehicle_id: str | None = None,
                   out: str | Path | None = None) -> ReplayResult:
    layout = KeyLayout()
    messages = list(read_messages(recording))
    configs = read_metadata(recording).get("coopdrive.config", {})
    vehicle_id = vehicle_id or _only_vehicle_of(configs, service_name, recording)
    config_key = f"{vehicle_id}/{service_name}"
    if config_key not in configs:
        raise ReplayError(f"{recording}: no recorded config for {config_key}; recorded: {', '.join(sorted(configs))}")
    cls = service_class(service_name)
    config = cls.Config.model_validate(json.loads(configs[config_key]))
    ctx = ReplayContext(vehicle_id=vehicle_id, service_name=service_name)
    service = cls(config, ctx)
    service.start()

    inputs: list[RecordedMessage] = []
    recorded_outputs: list[tuple[str, Message]] = []
    clocks = []
    for item in messages:
        vehicle, topic = layout.split(item.topic)
        header = getattr(item.message, "header", None)
        if vehicle == WORLD_ID and topic == "clock":
            clocks.append(item.message)
        elif header is not None and header.sender == service_name and vehicle == vehicle_id:
            recorded_outputs.append((item.topic, item.message))
        elif topic in ctx.handlers:
            inputs.append(item)
    inputs.sort(key=lambda m: m.message.header.sent_time_s)

    participants = ParticipantTracker()
    dispatcher = StepDispatcher(service_name, vehicle_id)
    next_input = 0
    steps = 0
    for clock in clocks:
        while next_input < len(inputs) and inputs[next_input].message.header.sent_time_s <= clock.time_s + TIME_EPSILON_S:
            vehicle, topic = layout.split(inputs[next_input].topic)
            dispatcher.add(Envelope(vehicle, topic, inputs[next_input].message))
            next_input += 1
        ctx.clock.set(clock.time_s)
        for participant, alive in participants.update(clock.participants):
            for handler in ctx.liveliness_handlers:
                handler(participant, alive)
        for envelope in dispatcher.eligible(clock.time_s):
            for source, handler in ctx.handlers.get(envelope.topic, ()):
                if source in ("*", envelope.vehicle_id):
                    handler(envelope)
        ctx.triggers.run_due(clock.time_s)
        steps += 1
    service.stop()
    # Live outputs stop where the recording stopped; drop replayed ones beyond the last recorded step.
    last_time = max((m.header.sent_time_s for _, m in recorded_outputs), default=-1.0)
    outputs = [(t, m) for t, m in ctx.outputs if m.header.sent_time_s <= last_time + TIME_EPSILON_S]
    if out is not None:
        recorder = McapRecorder(out, metadata={"coopdrive.config": {config_key: configs[config_key]}})
        for topic, message in outputs:
            recorder.write(topic, message)
        recorder.close()
    return ReplayResult(outputs, recorded_outputs, steps)


def _only_vehicle_of(configs: dict[str, str], service_name: str, recording) -> str:
    vehicles = sorted(key.split("/")[0] for key in configs if key.endswith(f"/{service_name}"))
    if len(vehicles) != 1:
        raise ReplayError(f"{recording}: choose --vehicle for {service_name}; recorded for: {', '.join(vehicles) or 'none'}")
    return vehicles[0]
