"""LocalDelivery: what a Zenoh session's own subscribers get from its own puts, handed over without Zenoh.

Services composed in one process (a vehicle's group, or a whole run with `--processes one`) share one session.
Zenoh delivers a put to the session's own subscribers on the putting thread, but its path (routing the key,
a Sample and its byte buffers per subscriber, the interpreter's lock given up and taken back around the call)
cost about 18 us of CPU a put in an 8-stack run: more than the subscribers' own decoding. So a Bus declares its
publishers for remote subscribers only and its subscribers for remote publishers only, and this registry takes
the session's own deliveries: the same bytes, the same attachment, on the putting thread and in the order of the
puts, as Zenoh's local delivery gave them. Each subscriber still parses its own copy of the message.
"""

from __future__ import annotations

import threading
from typing import Callable

import zenoh

# deliver(key, payload, attachment, schema): schema is the message's full protobuf name.
Deliver = Callable[[str, bytes, "bytes | None", str], None]


class LocalDelivery:
    def __init__(self) -> None:
        self._subscriptions: dict[int, tuple[zenoh.KeyExpr, Deliver]] = {}
        self._next_token = 0
        # key -> the deliveries whose key expression it matches; emptied whenever a subscription comes or goes.
        self._by_key: dict[str, tuple[Deliver, ...]] = {}
        self._lock = threading.Lock()

    def subscribe(self, key_expr: str, deliver: Deliver) -> int:
        """Registers a subscriber; returns the token that unsubscribes it."""
        with self._lock:
            token = self._next_token
            self._next_token += 1
            self._subscriptions[token] = (zenoh.KeyExpr(key_expr), deliver)
            self._by_key = {}
        return token

    def unsubscribe(self, token: int) -> None:
        with self._lock:
            self._subscriptions.pop(token, None)
            self._by_key = {}

    def matching(self, key: str) -> tuple[Deliver, ...]:
        found = self._by_key.get(key)
        if found is None:
            with self._lock:
                target = zenoh.KeyExpr(key)
                found = tuple(deliver for expr, deliver in self._subscriptions.values() if expr.intersects(target))
                self._by_key[key] = found
        return found

    def deliver(self, key: str, payload: bytes, attachment: bytes | None, schema: str) -> bool:
        """Hands the put to every local subscriber whose key expression matches; True if there was one. Each
        delivery must not raise (Bus guards its subscribers' callbacks), or the publisher would see the error."""
        deliveries = self.matching(key)
        for deliver in deliveries:
            deliver(key, payload, attachment, schema)
        return bool(deliveries)
