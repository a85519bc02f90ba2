"""StateStore: the latest messages and per-service activity, shared by the bus and HTTP threads.

Written by the service's worker thread (bus handlers), read by the HTTP server's threads. Message
times are on the vehicle clock (simulation time in the simulator); arrival times are wall
(monotonic) seconds, so rates stay meaningful when simulated time stalls or runs fast.
"""

from __future__ import annotations

import threading
from collections import deque
from dataclasses import dataclass

from google.protobuf.message import Message

# Upper bound on remembered arrivals per service, whatever the rate and window.
MAX_ARRIVALS_PER_SERVICE = 20_000


@dataclass(frozen=True)
class LatestMessage:
    message: Message
    sent_time_s: float


@dataclass(frozen=True)
class ServiceActivity:
    alive: bool
    # Vehicle-clock send time of the newest message from this service, None if none yet.
    last_sent_time_s: float | None
    message_rate_hz: float


@dataclass(frozen=True)
class StoreSnapshot:
    # The vehicle clock when the store last heard of it, None before the first tick.
    clock_s: float | None
    services: dict[str, ServiceActivity]
    latest: dict[str, LatestMessage]


class _RateMeter:
    """Arrivals in a sliding wall-time window."""

    def __init__(self, window_s: float):
        self._window_s = window_s
        self._arrivals: deque[float] = deque(maxlen=MAX_ARRIVALS_PER_SERVICE)
        self._first_arrival_s: float | None = None

    def add(self, wall_s: float) -> None:
        if self._first_arrival_s is None:
            self._first_arrival_s = wall_s
        self._arrivals.append(wall_s)

    def rate_hz(self, wall_s: float) -> float:
        while self._arrivals and self._arrivals[0] < wall_s - self._window_s:
            self._arrivals.popleft()
        count = len(self._arrivals)
        if count == 0 or self._first_arrival_s is None:
            return 0.0
        if wall_s - self._first_arrival_s >= self._window_s:
            return count / self._window_s
        # Younger than one window: the spacing of what arrived so far, not a diluted average.
        span_s = self._arrivals[-1] - self._arrivals[0]
        return (count - 1) / span_s if count >= 2 and span_s > 0 else 0.0


class StateStore:
    def __init__(self, services: list[str], rate_window_s: float):
        self._lock = threading.Lock()
        self._clock_s: float | None = None
        self._alive = {service: False for service in services}
        self._last_sent_s: dict[str, float] = {}
        self._rates = {service: _RateMeter(rate_window_s) for service in services}
        self._latest: dict[str, LatestMessage] = {}

    def note_clock(self, clock_s: float) -> None:
        with self._lock:
            self._clock_s = clock_s

    def set_alive(self, service: str, alive: bool) -> None:
        with self._lock:
            if service in self._alive:
                self._alive[service] = alive

    def record(self, service: str, topic: str, message: Message, sent_time_s: float, wall_s: float) -> None:
        """A message `service` published on `topic`; unknown services are ignored."""
        with self._lock:
            if service not in self._rates:
                return
            self._latest[topic] = LatestMessage(message, sent_time_s)
            previous = self._last_sent_s.get(service)
            self._last_sent_s[service] = sent_time_s if previous is None else max(previous, sent_time_s)
            self._rates[service].add(wall_s)

    def latest(self, topic: str) -> LatestMessage | None:
        with self._lock:
            return self._latest.get(topic)

    def snapshot(self, wall_s: float) -> StoreSnapshot:
        with self._lock:
            services = {
                service: ServiceActivity(alive=self._alive[service], last_sent_time_s=self._last_sent_s.get(service),
                                         message_rate_hz=self._rates[service].rate_hz(wall_s))
                for service in self._alive}
            return StoreSnapshot(clock_s=self._clock_s, services=services, latest=dict(self._latest))
