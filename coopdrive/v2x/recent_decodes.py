"""RecentDecodes: the UPER decodes of the last packets a process heard, shared by every codec in it.

Where stacks share a process (`--processes one`, what a sweep runs), every packet reaches each of them that is in
radio range, and each would decode the same bytes again: 79 % of an 8-stack run's UPER decodes were repeats. A
decode is a function of the bytes alone (the schemas are the packaged modules), so one decode serves them all.
The values are asn1tools' dicts and lists, handed to every caller as they are: they are read, never written (the
mappings build protobuf from them; tests/v2x/test_recent_decodes.py holds them to that).
"""

from __future__ import annotations

from collections import OrderedDict

# About a second of an 8-stack run's traffic: a packet reaches all its receivers within a few steps.
DEFAULT_CAPACITY = 512


class RecentDecodes:
    def __init__(self, capacity: int = DEFAULT_CAPACITY) -> None:
        self.capacity = capacity
        self._values: OrderedDict[bytes, dict] = OrderedDict()
        self.hits = 0
        self.misses = 0

    def get(self, uper: bytes) -> dict | None:
        value = self._values.get(uper)
        if value is None:
            self.misses += 1
        else:
            self.hits += 1
        return value

    def keep(self, uper: bytes, value: dict) -> None:
        """Remembers a decode, forgetting the oldest beyond capacity. The services of a process call this from
        their own threads: OrderedDict's popitem is one call under the interpreter's lock."""
        self._values[uper] = value
        while len(self._values) > self.capacity:
            try:
                self._values.popitem(last=False)
            except KeyError:
                return


# One per process: the decodes of every ItsCodec in it.
RECENT_DECODES = RecentDecodes()
