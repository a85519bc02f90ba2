"""What every log reader of `coopdrive import` hands the importer: timed messages and a count of what it read."""

from __future__ import annotations

from collections import Counter
from dataclasses import dataclass, field
from pathlib import Path

from google.protobuf.message import Message

from coopdrive.v1 import vehicle_pb2


class ImportFailure(ValueError):
    """A whole log cannot be imported (not a capture, no time in it); bad lines are counted instead."""


@dataclass
class TimedMessage:
    # Arrival time on the recording's time base (see importer.py): becomes the MCAP log time and header times.
    time_s: float
    topic: str
    message: Message

    def shift(self, offset_s: float) -> None:
        """Onto the recording's time base: the arrival time and, for a batch of CAN frames, each frame's own time
        (a replayed frame is read at the time it was on the bus, not at its batch's arrival)."""
        self.time_s += offset_s
        if isinstance(self.message, vehicle_pb2.CanFrames):
            for frame in self.message.frames:
                frame.timestamp_s += offset_s


@dataclass
class SourceReport:
    """One imported log: what came out of it and every line or packet that was wrong, counted per reason."""

    kind: str  # nmea, candump or pcap: the NAME of --offset
    path: Path
    offset_s: float = 0.0
    items_read: int = 0  # lines of a text log, packets of a capture
    messages: list[TimedMessage] = field(default_factory=list)
    bad: Counter = field(default_factory=Counter)
    # Items read and imported as they are although something about them is odd (time going back, unknown ids).
    notes: Counter = field(default_factory=Counter)

    @property
    def first_s(self) -> float | None:
        return min((m.time_s for m in self.messages), default=None)

    @property
    def last_s(self) -> float | None:
        return max((m.time_s for m in self.messages), default=None)

    def summary_line(self) -> str:
        span = "" if self.first_s is None else f", {self.first_s:.3f} to {self.last_s:.3f} s"
        shift = f" (shifted {self.offset_s:+.3f} s)" if self.offset_s else ""
        bad = ", ".join(f"{count} {reason}" for reason, count in sorted(self.bad.items())) or "none"
        line = (f"{self.kind} {self.path.name}: {self.items_read} read, {len(self.messages)} messages"
                f"{span}{shift}; bad: {bad}")
        if self.notes:
            line += "; notes: " + ", ".join(f"{count} {reason}" for reason, count in sorted(self.notes.items()))
        return line

    def as_dict(self) -> dict:
        return {"kind": self.kind, "file": str(self.path), "offset_s": self.offset_s, "read": self.items_read,
                "messages": len(self.messages), "first_s": self.first_s, "last_s": self.last_s,
                "bad": dict(self.bad), "notes": dict(self.notes)}
