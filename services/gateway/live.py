"""LiveBroadcaster: the live state on /ws, one producer and a bounded queue per client.

The producer builds each frame once and offers it to every client's queue without waiting; a
full queue loses its oldest frame. Each client is sent its frames by its own task, so a slow or
stuck client (whose sends block on a full socket) only ever loses its own frames: it never
slows the producer, the other clients, or the bus (which only writes to the store).
"""

from __future__ import annotations

import asyncio
import logging
from typing import Awaitable, Callable

# Behind by more than this many periods (a stalled loop): restart the schedule instead of bursting.
MAX_LAG_PERIODS = 2
log = logging.getLogger(__name__)


class LiveClient:
    def __init__(self, max_frames: int):
        self.queue: asyncio.Queue[str] = asyncio.Queue(max_frames)
        self.dropped = 0

    def offer(self, frame: str) -> bool:
        """Queues frame; True if the oldest waiting frame had to be dropped for it."""
        dropped = False
        if self.queue.full():
            self.queue.get_nowait()
            self.dropped += 1
            dropped = True
        self.queue.put_nowait(frame)
        return dropped


class LiveBroadcaster:
    def __init__(self, make_frame: Callable[[int], str], rate_hz: float, queue_frames: int,
                 on_drop: Callable[[], None] = lambda: None):
        self._make_frame = make_frame
        self._period_s = 1.0 / rate_hz
        self._queue_frames = queue_frames
        self._on_drop = on_drop
        self._clients: set[LiveClient] = set()
        self._task: asyncio.Task | None = None
        self._seq = 0

    @property
    def client_count(self) -> int:
        return len(self._clients)

    async def serve(self, send: Callable[[str], Awaitable[None]]) -> None:
        """Sends frames through `send` until it raises (the client went away); runs on the server's loop."""
        client = LiveClient(self._queue_frames)
        self._clients.add(client)
        if self._task is None or self._task.done():
            self._task = asyncio.get_running_loop().create_task(self._produce())
        try:
            while True:
                await send(await client.queue.get())
        finally:
            self._clients.discard(client)

    async def _produce(self) -> None:
        loop = asyncio.get_running_loop()
        due = loop.time()
        while self._clients:
            self._seq += 1
            try:
                frame = self._make_frame(self._seq)
            except Exception:  # noqa: BLE001 - one bad frame must not end the stream for every client
                log.exception("live frame %d could not be built", self._seq)
                frame = None
            for client in list(self._clients) if frame is not None else []:
                if client.offer(frame):
                    self._on_drop()
            due += self._period_s
            now = loop.time()
            if now - due > MAX_LAG_PERIODS * self._period_s:
                due = now
            await asyncio.sleep(max(0.0, due - now))
