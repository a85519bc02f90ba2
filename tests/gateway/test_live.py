"""The /ws live stream: frames at the configured rate, and a client that never reads only loses its own frames."""

import asyncio
import base64
import json
import os
import socket
import time

import pytest
from websockets.exceptions import InvalidStatus
from websockets.sync.client import connect

from conftest import TOKENS
from coopdrive.services.gateway.live import LiveBroadcaster, LiveClient
from coopdrive.v1 import scene_pb2

# Generous deadlines: a loaded 2-core machine may schedule the server late.
DEADLINE_S = 30.0
RECV_TIMEOUT_S = 10.0
# Enough objects that each frame is tens of kB, so a stuck client's socket buffers fill within seconds.
MANY_OBJECTS = 300


def test_a_full_client_queue_drops_its_oldest_frame():
    async def scenario():
        client = LiveClient(max_frames=2)
        assert not client.offer("1") and not client.offer("2")
        assert client.offer("3")
        return [client.queue.get_nowait() for _ in range(2)], client.dropped
    assert asyncio.run(scenario()) == (["2", "3"], 1)


def test_a_stuck_client_loses_frames_while_another_receives_every_one():
    received: list[str] = []
    drops: list[int] = []

    async def scenario():
        live = LiveBroadcaster(lambda seq: str(seq), rate_hz=25.0, queue_frames=3, on_drop=lambda: drops.append(1))

        async def stuck(frame: str) -> None:
            await asyncio.Event().wait()  # a send that never completes: a full socket

        async def quick(frame: str) -> None:
            received.append(frame)
            if len(received) == 20:
                raise ConnectionError("enough")

        stuck_task = asyncio.create_task(live.serve(stuck))
        with pytest.raises(ConnectionError):
            await live.serve(quick)
        stuck_task.cancel()

    asyncio.run(scenario())
    assert received == [str(seq) for seq in range(1, 21)]
    assert len(drops) >= 20 - 3 - 1


def ws_url(port: int) -> str:
    return f"ws://127.0.0.1:{port}/ws"


def frames(port: int, count: int, **options) -> list[dict]:
    with connect(ws_url(port), open_timeout=RECV_TIMEOUT_S, **options) as ws:
        return [json.loads(ws.recv(timeout=RECV_TIMEOUT_S)) for _ in range(count)]


def test_the_stream_carries_live_frames_that_follow_the_bus(make_gateway, feed):
    gateway = make_gateway(live_rate_hz=20.0)
    feed(gateway.ctx, speed_mps=12.0)
    first = frames(gateway.port, 3)
    assert [f["seq"] for f in first] == sorted(f["seq"] for f in first)
    assert first[-1]["speed_mps"] == 12.0 and first[-1]["gap_m"] == 30.0
    assert first[-1]["planner_state"] == "FOLLOWING" and first[-1]["stations"][0]["station_id"] == 4242
    feed(gateway.ctx, speed_mps=14.0)
    assert frames(gateway.port, 2)[-1]["speed_mps"] == 14.0


def test_a_closed_gateway_refuses_a_stream_without_a_token(make_gateway):
    gateway = make_gateway(readonly_open=False, tokens=TOKENS)
    with pytest.raises(InvalidStatus, match="403"):
        frames(gateway.port, 1)
    assert frames(gateway.port, 1, additional_headers={"Authorization": "Bearer observer-secret-1"})
    with connect(ws_url(gateway.port) + "?token=operator-secret-1", open_timeout=RECV_TIMEOUT_S) as ws:
        assert json.loads(ws.recv(timeout=RECV_TIMEOUT_S))["seq"] >= 1


def stuck_client(port: int) -> socket.socket:
    """Opens /ws with a tiny receive buffer and never reads a frame."""
    sock = socket.socket(socket.AF_INET, socket.SOCK_STREAM)
    sock.setsockopt(socket.SOL_SOCKET, socket.SO_RCVBUF, 4096)
    sock.connect(("127.0.0.1", port))
    key = base64.b64encode(os.urandom(16)).decode()
    sock.sendall((f"GET /ws HTTP/1.1\r\nHost: 127.0.0.1:{port}\r\nUpgrade: websocket\r\nConnection: Upgrade\r\n"
                  f"Sec-WebSocket-Key: {key}\r\nSec-WebSocket-Version: 13\r\n\r\n").encode())
    sock.settimeout(RECV_TIMEOUT_S)
    assert sock.recv(12).startswith(b"HTTP/1.1 101")
    return sock


def dropped_frames(gateway) -> float:
    for line in gateway.http.get("/metrics").text.splitlines():
        if line.startswith("coopdrive_gateway_ws_frames_dropped_total "):
            return float(line.split()[1])
    raise AssertionError("no dropped-frames counter in /metrics")


def test_a_client_that_never_reads_does_not_stop_another_receiving(make_gateway, feed):
    gateway = make_gateway(live_rate_hz=25.0, live_queue_frames=2)
    feed(gateway.ctx)
    scene = scene_pb2.Scene()
    for i in range(MANY_OBJECTS):
        obj = scene.objects.add(object_id=i + 1)
        obj.position.x_m, obj.position.y_m, obj.position.confidence = float(i), 1.0, 0.5
    gateway.ctx.deliver("scene", scene)
    slow = stuck_client(gateway.port)
    try:
        deadline = time.monotonic() + DEADLINE_S
        with connect(ws_url(gateway.port), open_timeout=RECV_TIMEOUT_S, max_size=None) as ws:
            seqs = []
            while dropped_frames(gateway) == 0:  # the stuck client's buffers are full: its frames now drop
                assert time.monotonic() < deadline, "the stuck client never lost a frame"
                seqs.append(json.loads(ws.recv(timeout=RECV_TIMEOUT_S))["seq"])
            before = len(seqs)
            started = time.monotonic()
            while time.monotonic() - started < 2.0:
                seqs.append(json.loads(ws.recv(timeout=RECV_TIMEOUT_S))["seq"])
        assert len(seqs) - before >= 10, "the reading client was held up by the stuck one"
        assert seqs == sorted(seqs)
    finally:
        slow.close()
