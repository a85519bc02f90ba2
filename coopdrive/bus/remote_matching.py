"""RemoteMatching: whether a subscriber of another session matches a publisher, asked of Zenoh only when it may
have changed.

Zenoh's matching status cost 48-120 us of CPU per ask in a busy process (the call gives the interpreter's lock up
and takes it back). Bus asks it before every put (a put nobody else hears stays out of Zenoh) and every quiet
topic's step marker (put_if_subscribed). The answer changes only when subscribers come or go, which Zenoh's
matching listener reports: the status is asked again only after such a report. A report that comes while the
status is being asked discards that answer, so an answer kept is never older than the last change reported.
"""

from __future__ import annotations

import threading

import zenoh


class RemoteMatching:
    def __init__(self, publisher: zenoh.Publisher, on_change_handler) -> None:
        """on_change_handler wraps the listener's callback as Zenoh wants it (Bus runs it on Zenoh's thread)."""
        self._publisher = publisher
        self._lock = threading.Lock()
        self._known: bool | None = None
        self._changes = 0
        # Declared before the first ask, so that no change after it goes unreported.
        self.listener = publisher.declare_matching_listener(on_change_handler(self._on_change))

    def _on_change(self, _status) -> None:
        with self._lock:
            self._changes += 1
            self._known = None

    def matching(self) -> bool:
        known = self._known
        if known is not None:
            return known
        with self._lock:
            changes = self._changes
        known = self._publisher.matching_status.matching
        with self._lock:
            if changes == self._changes:
                self._known = known
        return known
