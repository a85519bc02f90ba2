"""RouterDenials: the messages a router's access control refused, counted from Zenoh's own log.

Zenoh's Python API exposes no count of them: the access control only logs each decision, refusals and permissions
alike, at trace level (target zenoh::net::routing::interceptor::access_control, "... is unauthorized to Put (ingress)
on <key>"). When a key is first declared it also works out, and logs in the same words, what each kind of message
would get on it ("caching permissions for `<key>` ..." and a line per kind): those are not refusals of a message and
are not counted; a message judged later says "Using cached result: ...", and is. So the router's process turns that
target's trace on, takes Zenoh's log off its stdout through a pipe,
counts the refusals, and writes on stdout what the user's own filter asked for plus, at most once a period when it
changed, the count: "access control denials: N (last: <key> by <subject>)". Tracing every permitted message costs the
router some CPU: `coopdrive router --count-denials` asks for it.
"""

from __future__ import annotations

import os
import re
import sys
import threading
from typing import TextIO

ACCESS_CONTROL_TARGET = "zenoh::net::routing::interceptor::access_control"
DENIAL_TEXT = "is unauthorized to"
CACHING_TEXT = "caching permissions for `"
CACHED_TEXT = "Using cached result"
THREAD = re.compile(r"ThreadId\(\d+\)")
REPORT_PERIOD_S = 1.0


class RouterDenials:
    def __init__(self, user_filter: str | None):
        """`user_filter`: what the user asked of Zenoh's log (RUST_LOG), None for nothing but errors."""
        self.count = 0
        self.last = ""
        self._show_access_control = bool(user_filter) and ACCESS_CONTROL_TARGET.split("::")[-1] in user_filter
        self.log_filter = f"{user_filter or 'error'},{ACCESS_CONTROL_TARGET}=trace"
        self._reported = 0
        # Per Zenoh thread: the key whose permissions it is working out, while its lines are about that.
        self._caching: dict[str, str] = {}
        self._lock = threading.Lock()
        self._write_lock = threading.Lock()
        self._stop = threading.Event()
        self._out: TextIO | None = None
        self._threads: list[threading.Thread] = []

    def start(self) -> None:
        """From now, what the process writes on file descriptor 1 (Zenoh's log) is read here; Python's own output
        (sys.stdout) goes on to the real stdout."""
        saved = os.dup(1)
        self._out = os.fdopen(saved, "w", buffering=1)
        reading, writing = os.pipe()
        os.dup2(writing, 1)
        os.close(writing)
        sys.stdout.flush()
        sys.stdout = self._out
        self._threads = [threading.Thread(target=self._read, args=(reading,), name="router-log", daemon=True),
                         threading.Thread(target=self._report_changes, name="router-denials", daemon=True)]
        for thread in self._threads:
            thread.start()

    def close(self) -> None:
        """Gives file descriptor 1 back to stdout (the pipe ends: its reader stops) and reports the last count."""
        if self._out is None:
            return
        os.dup2(self._out.fileno(), 1)
        self._stop.set()
        for thread in self._threads:
            thread.join(timeout=5.0)
        self._report()

    def _read(self, reading: int) -> None:
        with os.fdopen(reading, "r", errors="replace") as lines:
            for line in lines:
                self._take(line)

    def _take(self, line: str) -> None:
        if ACCESS_CONTROL_TARGET not in line or self._show_access_control:
            self._write(line)
        if self._refusal(line):
            with self._lock:
                self.count += 1
                self.last = " ".join(line.split(DENIAL_TEXT, 1)[1].split())

    def _refusal(self, line: str) -> bool:
        """Whether the line tells a message refused, not a key's permissions worked out ahead: those come on the
        thread that logged "caching permissions" for that key last (a key Zenoh does not cache, one not declared,
        is judged afresh at each message, and counted then)."""
        thread = THREAD.search(line)
        thread = thread.group(0) if thread else ""
        if CACHING_TEXT in line:
            self._caching[thread] = line.split(CACHING_TEXT, 1)[1].split("`", 1)[0]
            return False
        if DENIAL_TEXT not in line:
            return False
        return CACHED_TEXT in line or not line.rstrip().endswith(f" on {self._caching.get(thread)}")

    def _report_changes(self) -> None:
        while not self._stop.wait(REPORT_PERIOD_S):
            self._report()

    def _report(self) -> None:
        with self._lock:
            count, last = self.count, self.last
            if count == self._reported:
                return
            self._reported = count
        self._write(f"access control denials: {count} (last: {last})\n")

    def _write(self, text: str) -> None:
        with self._write_lock:
            self._out.write(text)
            self._out.flush()
