"""Replay: feeds one service its recorded inputs, step by step, and collects what it publishes.

The service runs in this process with a ReplayContext instead of a bus. Each recorded
lockstep clock step k is replayed by first handing the dispatcher every recorded input sent up
to that step, then applying the same StepDispatcher rule the live runner used; a
deterministic service therefore publishes exactly what it published live.

A recording without a lockstep clock (made on a vehicle, or imported) replays on the wall-clock
path of replay_wall.py instead; replay_diff.py says how the outputs differ from the recorded ones.
"""

from __future__ import annotations

import logging
from collections.abc import Iterable
from dataclasses import dataclass, field
from pathlib import Path

from google.protobuf.message import Message

from coopdrive.bus import Envelope, KeyLayout
from coopdrive.bus.keys import WORLD_ID
from coopdrive.recording.reader import (RecordedMessage, read_messages, read_metadata, recorded_topics,
                                        recording_start_ns)
from coopdrive.recording.replay_config import ReplayError, missing_inputs_text, replay_config
from coopdrive.recording.replay_wall import run_wall_clock
from coopdrive.bus.publish_spool import NANOSECONDS, message_time_ns
from coopdrive.recording.writer import CONFIG_METADATA, McapRecorder, config_metadata
from coopdrive.runtime.dispatcher import TIME_EPSILON_S, StepDispatcher
from coopdrive.runtime.participants import ParticipantTracker
from coopdrive.runtime.pipeline import WORLD_SERVICE
from coopdrive.runtime.registry import service_class
from coopdrive.runtime.testing import MemoryContext
from coopdrive.visual import VisualChannels, recorded_road_map

__all__ = ["ReplayContext", "ReplayError", "ReplayResult", "TimeWindow", "replay_service"]


class ReplayContext(MemoryContext):
    """A ServiceContext backed by a recording instead of a bus: a MemoryContext on the recording's clock."""

    def __init__(self, vehicle_id: str, service_name: str) -> None:
        super().__init__(vehicle_id, service_name, log=logging.getLogger("coopdrive.replay"))
        self.handler_errors = 0  # wall-clock replay: inputs whose handler raised (live they are counted too)
        self.skipped_s = 0.0  # wall-clock replay: time without inputs the triggers did not run through


@dataclass(frozen=True)
class TimeWindow:
    """Part of a recording, in seconds from its first message: the service starts at from_s (as if started then)
    and its outputs are compared up to to_s (None: the end)."""

    from_s: float = 0.0
    to_s: float | None = None

    def __post_init__(self) -> None:
        if self.from_s < 0.0:
            raise ReplayError(f"--from {self.from_s:g}: a window starts at 0 s or later")
        if self.to_s is not None and self.to_s <= self.from_s:
            raise ReplayError(f"--to {self.to_s:g}: a window ends after it starts (--from {self.from_s:g})")

    def log_times_ns(self, recording_start_ns: int) -> tuple[int, int | None]:
        """[start, end) in the recording's log time."""
        end_ns = None if self.to_s is None else recording_start_ns + round(self.to_s * NANOSECONDS)
        return recording_start_ns + round(self.from_s * NANOSECONDS), end_ns

    def describe(self) -> str:
        return f"{self.from_s:g} s to {'the end' if self.to_s is None else f'{self.to_s:g} s'}"


@dataclass
class ReplayResult:
    outputs: list[tuple[str, Message]]
    recorded_outputs: list[tuple[str, Message]]
    steps: int
    mode: str = "lockstep"  # or "wall": inputs in arrival order, triggers on a clock driven by their times
    config_changed: bool = False  # --config or --set: differences are the point, not a failure
    notes: list[str] = field(default_factory=list)
    # A part of the recording only: the service starts within it, its state not the recorded one.
    window: TimeWindow | None = None
    # The service's counters when it stopped (replay_counts.py puts them in words).
    counters: dict[str, float] = field(default_factory=dict)

    @property
    def exact(self) -> bool:
        """Whether the outputs must be the recorded ones: a lockstep replay of the whole run with its own config."""
        return self.mode == "lockstep" and not self.config_changed and self.window is None

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
                   out: str | Path | None = None, config_file: str | Path | None = None,
                   overrides: list[str] | tuple[str, ...] = (), window: TimeWindow | None = None) -> ReplayResult:
    """Lockstep recordings (with world/clock) replay step by step as the run did; any other recording (a
    vehicle's, an import) replays its inputs in arrival order on a clock driven by their log times (see
    replay_wall.py). config_file replaces the recorded config, overrides (KEY=VALUE) change either; window: only
    that part of the recording is read and replayed (a long drive's minute in question)."""
    cls = service_class(service_name)
    layout = KeyLayout()
    metadata = read_metadata(recording)
    configs = metadata.get(CONFIG_METADATA, {})
    vehicle_id = vehicle_id or _only_vehicle_of(configs, service_name, recording)
    config_key = f"{vehicle_id}/{service_name}"
    config, notes = replay_config(cls, recording, config_key, configs, metadata, config_file, overrides)
    ctx = ReplayContext(vehicle_id=vehicle_id, service_name=service_name)
    service = cls(config, ctx)
    try:
        service.start()
    except Exception as error:  # e.g. a service that still opens its hardware under replay: one line, not a trace
        raise ReplayError(f"{service_name} did not start for the replay: {error}") from error

    topics = recorded_topics(recording)
    start_ns = recording_start_ns(recording)
    log_times_ns = window.log_times_ns(start_ns) if window is not None and start_ns is not None else (None, None)
    messages = read_messages(recording, [t for t in topics if _may_concern(t, layout, ctx, vehicle_id)],
                             *log_times_ns)
    inputs, recorded_outputs, clocks, drawn = _split(messages, layout, ctx, service_name, vehicle_id)
    if not inputs:
        service.stop()
        if window is not None:
            raise ReplayError(f"{recording}: no input of {service_name} on vehicle {vehicle_id} from "
                              f"{window.describe()} of the recording")
        raise ReplayError(missing_inputs_text(recording, service_name, vehicle_id, ctx, topics, layout))
    if clocks:
        steps = _run_lockstep(ctx, inputs, clocks, layout, service_name, vehicle_id)
    else:
        steps = run_wall_clock(ctx, inputs, recorded_outputs, layout)
    service.stop()
    if ctx.handler_errors:
        notes.append(f"{ctx.handler_errors} inputs made a handler of {service_name} fail (see the log)")
    if ctx.skipped_s:
        notes.append(f"skipped {ctx.skipped_s:.1f} s without inputs (logs not lined up? see import --offset)")
    if steps == 0:
        raise ReplayError(f"{recording}: replayed 0 steps through {service_name}: the recording's world/clock "
                          f"ends before its first input")
    # Live outputs stop where the recording stopped; drop replayed ones beyond the last recorded step.
    last_time = max((m.header.sent_time_s for _, m, _ in recorded_outputs), default=None)
    outputs = ctx.outputs if last_time is None or not clocks else [
        (t, m) for t, m in ctx.outputs if m.header.sent_time_s <= last_time + TIME_EPSILON_S]
    if window is not None:
        notes.append(f"replayed {window.describe()} of the recording: {service_name} started at {window.from_s:g} s "
                     f"with none of its recorded state, so its first outputs may differ while its estimates settle")
    result = ReplayResult(outputs, [(t, m) for t, m, _ in recorded_outputs], steps,
                          "lockstep" if clocks else "wall", bool(config_file or overrides), notes, window,
                          dict(service.counters))
    if out is not None:
        _write_replay(out, inputs + drawn, outputs, {config_key: config.model_dump_json()}, metadata)
    return result


def _may_concern(key: str, layout: KeyLayout, ctx: ReplayContext, vehicle_id: str) -> bool:
    """Whether a recorded topic can hold something _split keeps: the clock, an input, the vehicle's own outputs.
    An 8-vehicle recording's other channels are most of it."""
    parsed = layout.parse(key)
    if parsed is None:
        return False
    vehicle, topic = parsed
    sources = _sources(ctx, topic)
    return (vehicle == WORLD_ID and topic == "clock") or vehicle == vehicle_id or vehicle in sources or "*" in sources


def _split(messages: Iterable[RecordedMessage], layout: KeyLayout, ctx: ReplayContext, service_name: str,
           vehicle_id: str) -> tuple[list[RecordedMessage], list[tuple[str, Message, int]], list[Message],
                                     list[RecordedMessage]]:
    """(inputs: what the service subscribed to, recorded outputs with their log times, lockstep clocks, what else
    of the vehicle's the Foxglove channels draw from: the plan a replayed scene is drawn with)."""
    inputs, recorded_outputs, clocks, drawn = [], [], [], []
    visuals = VisualChannels(lambda *_: None)
    for item in messages:
        parsed = layout.parse(item.topic)
        if parsed is None:
            continue
        vehicle, topic = parsed
        header = getattr(item.message, "header", None)
        if vehicle == WORLD_ID and topic == "clock":
            clocks.append(item.message)
        elif _is_input(ctx, vehicle, topic, header, service_name):
            inputs.append(item)
        elif header is not None and header.sender == service_name and vehicle == vehicle_id:
            recorded_outputs.append((item.topic, item.message, item.log_time_ns))
        elif vehicle == vehicle_id and visuals.draws(item.topic):
            drawn.append(item)
    return inputs, recorded_outputs, clocks, drawn


def _is_input(ctx: ReplayContext, vehicle: str, topic: str, header, service_name: str) -> bool:
    """A topic the service subscribed to for this vehicle, even one it publishes itself (its driver side puts
    the GNSS bytes on gnss/nmea, its estimator reads them); through a subscription to every vehicle ("*"),
    only what others sent."""
    sources = _sources(ctx, topic)
    own = header is not None and header.sender == service_name
    return vehicle in sources or ("*" in sources and not own)


def _sources(ctx: ReplayContext, topic: str) -> set[str]:
    """The vehicles (or "*") whose `topic` the service subscribed to."""
    return {source for source, _ in ctx.handlers.get(topic, ())}


def _run_lockstep(ctx: ReplayContext, inputs: list[RecordedMessage], clocks: list[Message], layout: KeyLayout,
                  service_name: str, vehicle_id: str) -> int:
    inputs.sort(key=lambda m: m.message.header.sent_time_s)
    participants = ParticipantTracker()
    dispatcher = StepDispatcher(service_name, vehicle_id)
    next_input = 0
    steps = 0
    for clock in clocks:
        while next_input < len(inputs) and inputs[next_input].message.header.sent_time_s <= clock.time_s + TIME_EPSILON_S:
            vehicle, topic = layout.split(inputs[next_input].topic)
            dispatcher.add(Envelope(vehicle, topic, _as_hardware_input(inputs[next_input].message, service_name)))
            next_input += 1
        ctx.clock.set(clock.time_s)
        for participant, alive in participants.update(clock.participants):
            for handler in ctx.liveliness_handlers:
                handler(participant, alive)
        for envelope in dispatcher.eligible(clock.time_s):
            ctx.dispatch(envelope)
        ctx.triggers.run_due(clock.time_s)
        steps += 1
    return steps


def _as_hardware_input(message: Message, service_name: str) -> Message:
    """What the service's own driver side published (gnss/nmea: the bytes its port delivered) was read live
    within the step of the world's mark that announced them, before its own outputs: replayed, it goes to the
    dispatcher as data from upstream of the service (the world's rank), so it is handled in that same step
    rather than a step later as the service's own feedback would be."""
    if message.header.sender != service_name:
        return message
    hardware = type(message)()
    hardware.CopyFrom(message)
    hardware.header.sender = WORLD_SERVICE
    return hardware


def _write_replay(out: str | Path, recorded: list[RecordedMessage], outputs: list[tuple[str, Message]],
                  configs: dict[str, str], metadata: dict[str, dict[str, str]]) -> None:
    """The recorded messages kept (inputs, what the Foxglove channels draw from) at their log times and the replayed
    outputs at their sent times, in time order as the run's recording was written, with the config used; its
    Foxglove channels drawn on the recorded lane map."""
    recorded_configs = metadata.get(CONFIG_METADATA, {})
    kept = {name: values for name, values in metadata.items() if name != CONFIG_METADATA}
    recorder = McapRecorder(out, metadata={**kept, **config_metadata(configs)},
                            road_map=recorded_road_map(recorded_configs))
    timeline = [(item.log_time_ns, item.topic, item.message) for item in recorded]
    timeline += [(message_time_ns(message), topic, message) for topic, message in outputs]
    timeline.sort(key=lambda entry: entry[0])
    try:
        for log_time_ns, topic, message in timeline:
            recorder.write(topic, message, log_time_ns=log_time_ns)
    finally:
        recorder.close()


def _only_vehicle_of(configs: dict[str, str], service_name: str, recording) -> str:
    """The vehicle a service ran on, from the recorded configs."""
    vehicles = sorted(key.split("/")[0] for key in configs if key.endswith(f"/{service_name}"))
    if len(vehicles) != 1:
        raise ReplayError(f"{recording}: choose --vehicle for {service_name}; recorded for: {', '.join(vehicles) or 'none'}")
    return vehicles[0]
