"""How a replay's outputs differ from the recorded ones: per topic the counts, and per field how far they moved.

Messages are paired per topic by header.sample_time_s: each recorded message with the replayed one nearest in
time, within half the recorded messages' typical spacing (a lockstep replay pairs exactly; a wall-clock one
pairs a periodic output with the one the replay made for the same period); messages without distinct sample
times are paired by header.sequence. Numeric fields give the largest and
the RMS difference (angles in _rad and _deg wrapped, so 359 and 1 degrees are 2 apart); text and enum fields
how many pairs differ. Header fields are left out: sequence numbers and send times say nothing about the
service's result. Diagnostics are left out too: the replay runs without the runtime that publishes them.
"""

from __future__ import annotations

import bisect
import math
from dataclasses import dataclass, field
from statistics import median

from google.protobuf.message import Message

from coopdrive.bus.keys import KeyLayout
from coopdrive.recording.flatten import flatten, numeric_fields

SKIPPED_TOPIC_PARTS = ("diagnostics/",)
# When a topic has a single recorded message there is no spacing to go by.
DEFAULT_PAIRING_WINDOW_S = 0.5


@dataclass
class FieldDifference:
    name: str
    pairs: int = 0
    max_abs: float = 0.0
    sum_squares: float = 0.0
    differing: int = 0  # pairs whose value is not the same

    @property
    def rms(self) -> float:
        return math.sqrt(self.sum_squares / self.pairs) if self.pairs else 0.0

    def as_dict(self) -> dict:
        return {"pairs": self.pairs, "differing": self.differing, "max_abs": self.max_abs, "rms": self.rms}


@dataclass
class TopicDifference:
    topic: str
    recorded: int
    replayed: int
    paired: int = 0
    numeric: dict[str, FieldDifference] = field(default_factory=dict)
    other: dict[str, FieldDifference] = field(default_factory=dict)

    def moved(self) -> list[FieldDifference]:
        """Fields that differ in at least one pair, numbers first, each group by name."""
        return ([f for _, f in sorted(self.numeric.items()) if f.differing]
                + [f for _, f in sorted(self.other.items()) if f.differing])

    def as_dict(self) -> dict:
        return {"topic": self.topic, "recorded": self.recorded, "replayed": self.replayed, "paired": self.paired,
                "moved": {f.name: f.as_dict() for f in self.moved()},
                "unchanged": sorted(name for name, f in {**self.numeric, **self.other}.items() if not f.differing)}


def compare_outputs(replayed: list[tuple[str, Message]], recorded: list[tuple[str, Message]]) -> list[TopicDifference]:
    by_topic_replayed, by_topic_recorded = _by_topic(replayed), _by_topic(recorded)
    differences = []
    for topic in sorted(set(by_topic_replayed) | set(by_topic_recorded)):
        mine, theirs = by_topic_replayed.get(topic, []), by_topic_recorded.get(topic, [])
        difference = TopicDifference(topic, len(theirs), len(mine))
        for replayed_message, recorded_message in _pairs(mine, theirs):
            difference.paired += 1
            replayed_fields = flatten(replayed_message)
            # A deterministic replay gives back the very message: flattening it twice would find nothing more.
            same = replayed_message == recorded_message
            _compare(difference, replayed_fields, replayed_fields if same else flatten(recorded_message))
        differences.append(difference)
    return differences


def _by_topic(items: list[tuple[str, Message]]) -> dict[str, list[Message]]:
    layout = KeyLayout()
    grouped: dict[str, list[Message]] = {}
    for key, message in items:
        if any(part in key for part in SKIPPED_TOPIC_PARTS):
            continue
        vehicle, topic = layout.parse(key) or ("", key)
        grouped.setdefault(f"{vehicle}/{topic}", []).append(message)
    for messages in grouped.values():
        messages.sort(key=lambda m: m.header.sample_time_s)
    return grouped


def _pairs(replayed: list[Message], recorded: list[Message]) -> list[tuple[Message, Message]]:
    if not replayed or not recorded:
        return []
    times = [m.header.sample_time_s for m in replayed]
    recorded_times = [m.header.sample_time_s for m in recorded]
    if len(set(recorded_times)) == 1 and len(recorded) > 1:  # no sample times to go by: in sequence order
        def by_sequence(messages):
            return sorted(messages, key=lambda m: m.header.sequence)

        return list(zip(by_sequence(replayed), by_sequence(recorded)))
    gaps = [b - a for a, b in zip(recorded_times, recorded_times[1:]) if b > a]
    window_s = median(gaps) / 2 if gaps else DEFAULT_PAIRING_WINDOW_S
    pairs, used = [], set()
    for message, time_s in zip(recorded, recorded_times):
        index = bisect.bisect_left(times, time_s)
        candidates = [i for i in (index - 1, index) if 0 <= i < len(times) and i not in used]
        if not candidates:
            continue
        best = min(candidates, key=lambda i: abs(times[i] - time_s))
        if abs(times[best] - time_s) <= window_s + 1e-9:
            used.add(best)
            pairs.append((replayed[best], message))
    return pairs


def _compare(difference: TopicDifference, replayed: dict, recorded: dict) -> None:
    replayed_numbers, recorded_numbers = numeric_fields(replayed), numeric_fields(recorded)
    for name in replayed.keys() & recorded.keys():
        if name.startswith("header."):
            continue
        if name in replayed_numbers and name in recorded_numbers:
            delta = _wrapped(name, replayed_numbers[name] - recorded_numbers[name])
            entry = difference.numeric.setdefault(name, FieldDifference(name))
            entry.max_abs = max(entry.max_abs, abs(delta))
            entry.sum_squares += delta * delta
        else:
            delta = 0.0 if replayed[name] == recorded[name] else 1.0
            entry = difference.other.setdefault(name, FieldDifference(name))
        entry.pairs += 1
        entry.differing += delta != 0.0


def _wrapped(name: str, delta: float) -> float:
    turn = 2 * math.pi if name.endswith("_rad") else 360.0 if name.endswith("_deg") else None
    if turn is None or not math.isfinite(delta):
        return delta
    return (delta + turn / 2) % turn - turn / 2


def table(differences: list[TopicDifference]) -> str:
    """The differences as text: a line per topic, then a line per field that moved."""
    lines = [f"{'topic':<28} {'recorded':>9} {'replayed':>9} {'paired':>7}  fields that moved"]
    for d in differences:
        moved = d.moved()
        lines.append(f"{d.topic:<28} {d.recorded:>9} {d.replayed:>9} {d.paired:>7}  {len(moved) or 'none'}")
        for f in moved:
            if f.name in d.numeric:
                lines.append(f"    {f.name:<40} max |diff| {f.max_abs:<12.6g} rms {f.rms:<12.6g} "
                             f"in {f.differing}/{f.pairs}")
            else:
                lines.append(f"    {f.name:<40} differs in {f.differing}/{f.pairs}")
    return "\n".join(lines)
