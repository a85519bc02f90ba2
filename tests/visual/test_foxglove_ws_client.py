"""The tests' Foxglove WebSocket client subscribes again to a channel the server answered with "Unknown channel ID"
(the SDK server's race between advertising a new channel and knowing it), and then gets its messages."""

import json

from tests.visual import foxglove_ws_client
from tests.visual.foxglove_ws_client import MESSAGE_DATA, MESSAGE_HEADER, watch


class ScriptedServer:
    """A socket that plays a server's frames in order and keeps what the client sent."""

    def __init__(self, frames):
        self.frames, self.sent = list(frames), []

    def recv(self, timeout=None):
        if not self.frames:
            raise TimeoutError
        return self.frames.pop(0)

    def send(self, text):
        self.sent.append(json.loads(text))

    def __enter__(self):
        return self

    def __exit__(self, *_):
        return False


def data(subscription: int, payload: bytes) -> bytes:
    return MESSAGE_HEADER.pack(MESSAGE_DATA, subscription, 0) + payload


def test_a_subscription_the_server_did_not_know_yet_is_made_again_and_then_served(monkeypatch):
    server = ScriptedServer([
        json.dumps({"op": "advertise", "channels": [{"id": 7, "topic": "fresh"}, {"id": 3, "topic": "old"}]}),
        data(2, b"old-1"),
        json.dumps({"op": "status", "level": 2, "message": "Unknown channel ID: 7"}),
        data(1, b"fresh-1"), data(2, b"old-2"),
    ])
    monkeypatch.setattr(foxglove_ws_client, "_connect_when_up", lambda url, deadline: server)
    monkeypatch.setattr(foxglove_ws_client, "RESUBSCRIBE_AFTER_S", 0.0)
    received = watch("ws://scripted", ["fresh", "old"], 1.0, 0.2)
    assert [s["subscriptions"] for s in server.sent] == [
        [{"id": 1, "channelId": 7}, {"id": 2, "channelId": 3}], [{"id": 1, "channelId": 7}]]
    assert received.resubscribed == 1
    assert [p for _, p in received.messages["fresh"]] == [b"fresh-1"]
    assert [p for _, p in received.messages["old"]] == [b"old-1", b"old-2"]


def test_a_status_about_a_channel_never_advertised_is_not_answered(monkeypatch):
    server = ScriptedServer([json.dumps({"op": "advertise", "channels": [{"id": 3, "topic": "old"}]}),
                             json.dumps({"op": "status", "level": 2, "message": "Unknown channel ID: 99"})])
    monkeypatch.setattr(foxglove_ws_client, "_connect_when_up", lambda url, deadline: server)
    received = watch("ws://scripted", ["old"], 1.0, 0.1)
    assert len(server.sent) == 1 and received.resubscribed == 0
