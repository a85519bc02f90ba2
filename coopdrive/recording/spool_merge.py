"""The spools a recorded run's processes write (coopdrive/bus/publish_spool.py), merged into its recording in time
order while the run goes on.

Messages of one time keep a fixed order, by the spool's name (the launcher names each after its process and its
start) and then as the process sent them, so a recording's order does not depend on when its messages arrived
anywhere, nor on when the merge read them: the merge takes the earliest of the spools' next messages, as a merge
of the finished files would, and waits while a spool that may still be written has no next message yet. Merged as
it goes, a run's recording is nearly whole when the run stops, and a stop takes the same time after a minute or an
hour (a run stopped by SIGTERM ends within 3 s, docs/how-to/record-replay.md).
"""

from __future__ import annotations

import heapq
import logging
import threading
from collections import deque
from dataclasses import dataclass, field
from pathlib import Path
from typing import Callable

from google.protobuf.message import DecodeError, Message

from coopdrive.bus.type_registry import message_class
from coopdrive.recording.spool_tail import SpooledMessage, SpoolTail

log = logging.getLogger(__name__)

SPOOL_SUFFIX = ".spool.mcap"
# How often a following merge reads the spools: what a stop has left to merge is about this much of the run.
FOLLOW_PERIOD_S = 0.2


@dataclass
class SpoolMergeStats:
    spools: int = 0
    messages: int = 0
    # Messages left out, each with a warning: a type this build does not know, or bytes that do not parse.
    unreadable: int = 0
    # Spools whose last record was cut short (a process killed while writing it), or unreadable from some record on.
    cut_spools: list[str] = field(default_factory=list)


def spool_paths(spool_dir: Path) -> list[Path]:
    return sorted(spool_dir.glob(f"*{SPOOL_SUFFIX}"))


def merge_spools(spool_dir: Path, write: Callable[[str, Message], None]) -> SpoolMergeStats:
    """Calls write(key, message) for every message of the finished spools in `spool_dir`, in time order."""
    merge = SpoolMerge(write)
    for path in spool_paths(spool_dir):
        merge.add(path)
    return merge.finish()


class SpoolMerge:
    """Calls write(key, message) for each spooled message as soon as its place in the recording is known."""

    def __init__(self, write: Callable[[str, Message], None]):
        self._write = write
        self._tails: dict[str, SpoolTail] = {}
        self._waiting: dict[str, deque[SpooledMessage]] = {}
        # The next message of each spool that has one.
        self._heads: list[SpooledMessage] = []
        # Spools that may still be written and have no next message: the merge waits for them.
        self._starved: set[str] = set()
        self._ended: set[str] = set()
        self._writer_gone: set[str] = set()
        self._lock = threading.Lock()
        self._stop = threading.Event()
        self._follower: threading.Thread | None = None
        self.stats = SpoolMergeStats()

    def add(self, path: Path) -> None:
        """A spool a process is about to write (or has written): the merge waits for its messages."""
        with self._lock:
            self._tails[path.name] = SpoolTail(path)
            self._waiting[path.name] = deque()
            self._starved.add(path.name)
            self.stats.spools += 1

    def writer_gone(self, path: Path) -> None:
        """The process writing the spool has ended: what it holds now is all it will hold."""
        with self._lock:
            self._writer_gone.add(path.name)

    def follow(self, period_s: float = FOLLOW_PERIOD_S) -> None:
        """Merges on a thread of its own every `period_s` until finish()."""
        self._follower = threading.Thread(target=self._follow, args=(period_s,), name="spool-merge", daemon=True)
        self._follower.start()

    def step(self) -> None:
        """Reads what the spools gained and writes every message whose place is now known."""
        with self._lock:
            for name, tail in self._tails.items():
                if name not in self._ended:
                    self._read(name, tail, ended=name in self._writer_gone)
            self._write_known()

    def finish(self) -> SpoolMergeStats:
        """Every spool's process has ended: merges the rest (warning of each cut spool and left-out message)."""
        if self._follower is not None:
            self._stop.set()
            self._follower.join()
        with self._lock:
            self._writer_gone.update(self._tails)
        self.step()
        return self.stats

    def _follow(self, period_s: float) -> None:
        while not self._stop.wait(period_s):
            try:
                self.step()
            except Exception:  # noqa: BLE001 - said, and the rest is merged at finish
                log.exception("recording: merging the spools during the run failed; the rest is merged at the end")
                return

    def _read(self, name: str, tail: SpoolTail, ended: bool) -> None:
        # `ended` was learned before this read, so the read takes everything the process wrote.
        waiting = self._waiting[name]
        was_empty = not waiting
        waiting.extend(tail.read_new())
        if ended:
            self._ended.add(name)
            if tail.close_out():
                self.stats.cut_spools.append(name)
        if was_empty and waiting:
            heapq.heappush(self._heads, waiting[0])
        if waiting or name in self._ended:
            self._starved.discard(name)

    def _write_known(self) -> None:
        """Writes the earliest of the spools' next messages while no spool that may still grow is without one."""
        while self._heads and not self._starved:
            earliest = heapq.heappop(self._heads)
            waiting = self._waiting[earliest.spool_name]
            waiting.popleft()
            if waiting:
                heapq.heappush(self._heads, waiting[0])
            elif earliest.spool_name not in self._ended:
                self._starved.add(earliest.spool_name)
            message = _decoded(earliest)
            if message is None:
                self.stats.unreadable += 1
                continue
            self._write(earliest.key, message)
            self.stats.messages += 1


def _decoded(spooled: SpooledMessage) -> Message | None:
    cls = message_class(spooled.type_name)
    if cls is None:
        log.warning("recording: left out a message on %s of unknown type %r", spooled.key, spooled.type_name)
        return None
    message = cls()
    try:
        message.ParseFromString(spooled.payload)
    except DecodeError as error:
        log.warning("recording: left out a malformed %s on %s: %s", spooled.type_name, spooled.key, error)
        return None
    return message
