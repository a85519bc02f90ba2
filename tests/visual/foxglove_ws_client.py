"""A minimal Foxglove WebSocket client on the `websockets` package: it reads the advertised channels, subscribes to
some and decodes binary message frames (opcode 0x01, subscription id u32, log time u64, payload; little-endian).

The protocol is foxglove.websocket.v1; the Foxglove SDK's server (0.30) names it foxglove.sdk.v1 in the
WebSocket handshake and refuses a connection offering only the old name, so the client offers both.

The SDK's server (0.30.3) can advertise a new channel to a client a moment before it knows the channel itself: a
subscription sent in that moment is answered with the status "Unknown channel ID: N" and never served (seen under
load, about one subscription in fifty made within milliseconds of the channel's creation, in a loop of our own
against a bare server). The client subscribes to such a channel again, as a Foxglove app would have to."""

from __future__ import annotations

import json
import re
import struct
import time
from dataclasses import dataclass, field

from websockets.sync.client import connect

SUBPROTOCOLS = ["foxglove.sdk.v1", "foxglove.websocket.v1"]
MESSAGE_DATA = 0x01
MESSAGE_HEADER = struct.Struct("<BIQ")
UNKNOWN_CHANNEL = re.compile(r"Unknown channel ID: (\d+)")
# How long to wait before subscribing again to a channel the server said it did not know.
RESUBSCRIBE_AFTER_S = 0.1


@dataclass
class Received:
    channels: dict[int, dict] = field(default_factory=dict)  # channel id -> its advertisement
    messages: dict[str, list[tuple[int, bytes]]] = field(default_factory=dict)  # topic -> [(log time ns, payload)]
    # Channel ids the server answered a subscription to with "Unknown channel ID", not yet subscribed again.
    refused: set[int] = field(default_factory=set)
    resubscribed: int = 0

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
        _subscribe(socket, received, subscriptions)
        end = time.monotonic() + listen_s
        while time.monotonic() < end:
            _read(socket, received, subscriptions, max(0.0, end - time.monotonic()))
            if received.refused:
                time.sleep(RESUBSCRIBE_AFTER_S)
                again = {number: topic for number, topic in subscriptions.items()
                         if (received.channel_by_topic(topic) or {}).get("id") in received.refused}
                received.refused.clear()
                received.resubscribed += len(again)
                _subscribe(socket, received, again)
    return received


def _subscribe(socket, received: Received, subscriptions: dict[int, str]) -> None:
    if subscriptions:
        socket.send(json.dumps({"op": "subscribe", "subscriptions": [
            {"id": number, "channelId": received.channel_by_topic(topic)["id"]}
            for number, topic in subscriptions.items()]}))


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
        elif message.get("op") == "status":
            unknown = UNKNOWN_CHANNEL.search(message.get("message", ""))
            if unknown and int(unknown.group(1)) in received.channels:
                received.refused.add(int(unknown.group(1)))
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
