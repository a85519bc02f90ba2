"""A minimal Foxglove WebSocket client on the `websockets` package: it reads the advertised channels, subscribes to
some and decodes binary message frames (opcode 0x01, subscription id u32, log time u64, payload; little-endian).

The protocol is foxglove.websocket.v1; the Foxglove SDK's server (0.30) names it foxglove.sdk.v1 in the
WebSocket handshake and refuses a connection offering only the old name, so the client offers both."""

from __future__ import annotations

import json
import struct
import time
from dataclasses import dataclass, field

from websockets.sync.client import connect

SUBPROTOCOLS = ["foxglove.sdk.v1", "foxglove.websocket.v1"]
MESSAGE_DATA = 0x01
MESSAGE_HEADER = struct.Struct("<BIQ")


@dataclass
class Received:
    channels: dict[int, dict] = field(default_factory=dict)  # channel id -> its advertisement
    messages: dict[str, list[tuple[int, bytes]]] = field(default_factory=dict)  # topic -> [(log time ns, payload)]

    def channel_by_topic(self, topic: str) -> dict | None:
        return next((c for c in self.channels.values() if c["topic"] == topic), None)


def watch(url: str, wanted_topics: list[str], advertise_timeout_s: float, listen_s: float) -> Received:
    """Waits up to advertise_timeout_s for the wanted topics' channels, subscribes to them, listens for listen_s."""
    received = Received()
    deadline = time.monotonic() + advertise_timeout_s
    with _connect_when_up(url, deadline) as socket:
        while any(received.channel_by_topic(t) is None for t in wanted_topics) and time.monotonic() < deadline:
            _read(socket, received, {}, 0.5)
        subscriptions = {}
        for number, topic in enumerate(t for t in wanted_topics if received.channel_by_topic(t)):
            subscriptions[number + 1] = topic
            received.messages[topic] = []
        socket.send(json.dumps({"op": "subscribe", "subscriptions": [
            {"id": number, "channelId": received.channel_by_topic(topic)["id"]}
            for number, topic in subscriptions.items()]}))
        end = time.monotonic() + listen_s
        while time.monotonic() < end:
            _read(socket, received, subscriptions, max(0.0, end - time.monotonic()))
    return received


def _read(socket, received: Received, subscriptions: dict[int, str], timeout_s: float) -> None:
    try:
        frame = socket.recv(timeout=timeout_s)
    except TimeoutError:
        return
    if isinstance(frame, str):
        message = json.loads(frame)
        if message.get("op") == "advertise":
            received.channels.update({c["id"]: c for c in message["channels"]})
        elif message.get("op") == "unadvertise":
            for channel_id in message["channelIds"]:
                received.channels.pop(channel_id, None)
        return
    opcode, subscription, log_time_ns = MESSAGE_HEADER.unpack_from(frame)
    if opcode == MESSAGE_DATA and subscription in subscriptions:
        received.messages[subscriptions[subscription]].append((log_time_ns, frame[MESSAGE_HEADER.size:]))


def _connect_when_up(url: str, deadline: float):
    """The server may still be starting: try again until the deadline."""
    while True:
        try:
            return connect(url, subprotocols=SUBPROTOCOLS, open_timeout=max(1.0, deadline - time.monotonic()),
                           max_size=None)
        except OSError:
            if time.monotonic() > deadline:
                raise
            time.sleep(0.2)
