"""candump-format (.log) recording and replay through python-can's Logger and LogReader.

The same files work with can-utils (`log2asc`, `canplayer` on the vehicle) and `python -m can.player`.
"""

from collections.abc import Iterable, Iterator
from pathlib import Path

import can

CANDUMP_SUFFIX = ".log"
DEFAULT_CHANNEL = "vcan0"


class CandumpLogger:
    """Writes frames to a candump .log file; usable as a context manager or a python-can Listener."""

    def __init__(self, path: str | Path, channel: str = DEFAULT_CHANNEL):
        path = Path(path)
        if path.suffix != CANDUMP_SUFFIX:
            raise ValueError(f"a candump log must end in {CANDUMP_SUFFIX}: {path}")
        self.path = path
        self.channel = channel
        self._writer = can.Logger(str(path))
        self.frames_written = 0

    def write(self, msg: can.Message) -> None:
        if msg.channel is None:
            msg = can.Message(timestamp=msg.timestamp, arbitration_id=msg.arbitration_id,
                              is_extended_id=msg.is_extended_id, data=msg.data, channel=self.channel,
                              is_remote_frame=msg.is_remote_frame, is_error_frame=msg.is_error_frame)
        self._writer.on_message_received(msg)
        self.frames_written += 1

    def write_all(self, messages: Iterable[can.Message]) -> None:
        for msg in messages:
            self.write(msg)

    def on_message_received(self, msg: can.Message) -> None:
        self.write(msg)

    def stop(self) -> None:
        self._writer.stop()

    def __enter__(self) -> "CandumpLogger":
        return self

    def __exit__(self, *exc_info) -> None:
        self.stop()


def read_candump(path: str | Path) -> Iterator[can.Message]:
    """Frames of a candump .log file in file order, with their recorded timestamps."""
    yield from can.LogReader(str(path))
