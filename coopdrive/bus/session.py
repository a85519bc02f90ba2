"""Bus: a Zenoh session that publishes and subscribes typed protobuf messages.

Scouting by multicast is off: peers find each other through explicit endpoints (and Zenoh's
gossip completes the mesh). Callbacks run on Zenoh's threads, so they must be short; the
service runtime only enqueues there. Puts reach the session's own subscribers (the other services of a
process) through LocalDelivery, on the putting thread, and other sessions' through Zenoh.
"""

from __future__ import annotations

import json
import logging
import os
import threading
from dataclasses import dataclass, field
from typing import Any, Callable, NamedTuple

import zenoh
from google.protobuf.message import DecodeError, Message

from coopdrive.bus.bus_mode import MTLS, bus_mode
from coopdrive.bus.credentials_error import REMEDY, REQUIRED_MODE_VARIABLE, BusCredentialsError
from coopdrive.bus.keys import KeyLayout
from coopdrive.bus.local_delivery import LocalDelivery
from coopdrive.bus.remote_matching import RemoteMatching
from coopdrive.bus.topics import Topic, topic_named
from coopdrive.bus.type_registry import message_class
from coopdrive.bus.publish_spool import is_recorded, process_spool

log = logging.getLogger(__name__)

# Set to 1, a session's own subscribers get its puts through Zenoh, as before LocalDelivery: the benchmarks'
# baseline (bench/bench_stacks.py). Read when a Bus opens, since services are forked from a preloaded server.
LOCAL_BY_ZENOH_VARIABLE = "COOPDRIVE_BUS_LOCAL_BY_ZENOH"


@dataclass
class BusConfig:
    # Endpoints to connect to, e.g. ["tcp/127.0.0.1:7447"] (the launcher's hub or a zenohd router).
    connect: list[str] = field(default_factory=list)
    # Endpoints to listen on; port 0 picks a free port, which gossip tells the other peers.
    listen: list[str] = field(default_factory=lambda: ["tcp/127.0.0.1:0"])
    mode: str = "peer"
    # Optional path to a Zenoh JSON5 config file merged first (TLS, access control).
    zenoh_config_file: str | None = None

    def to_zenoh(self) -> zenoh.Config:
        if self.zenoh_config_file and not os.path.isfile(self.zenoh_config_file):
            raise BusCredentialsError(f"no bus config {self.zenoh_config_file}: {REMEDY}")
        config = zenoh.Config.from_file(self.zenoh_config_file) if self.zenoh_config_file else zenoh.Config()
        config.insert_json5("scouting/multicast/enabled", "false")
        if json.loads(config.get_json("mode")) == "client":
            # A client of the router (`coopdrive pki bus` writes these): it listens nowhere, so nothing reaches it but
            # through the router's access control; its file names the router unless the command line does.
            if self.connect:
                config.insert_json5("connect/endpoints", json.dumps(self.connect))
            return config
        config.insert_json5("mode", json.dumps(self.mode))
        config.insert_json5("listen/endpoints", json.dumps(self.listen))
        config.insert_json5("connect/endpoints", json.dumps(self.connect))
        return config


class Envelope(NamedTuple):
    """A received message with where it came from."""

    vehicle_id: str
    topic: str
    message: Message
    # Zenoh attachment sent with the message: a lockstep publisher's step marker (see runtime/runner.py).
    attachment: bytes | None = None


class Bus:
    def __init__(self, config: BusConfig, layout: KeyLayout | None = None):
        self.layout = layout or KeyLayout()
        zenoh_config = config.to_zenoh()
        # "mtls", "plain-loopback" or "plain" (bus_mode.py): what the diagnostics and the gateway's /health tell.
        self.mode = bus_mode(zenoh_config)
        _check_required_mode(self.mode)
        self._session = _open(zenoh_config)
        self._owns_session = True
        self._local = LocalDelivery()
        # Where Zenoh takes a put and brings a sample: other sessions only, unless the baseline asks for Zenoh here too.
        self._zenoh_reach = (zenoh.Locality.ANY if os.environ.get(LOCAL_BY_ZENOH_VARIABLE) == "1"
                             else zenoh.Locality.REMOTE)
        self._start_own_state()

    def _start_own_state(self) -> None:
        """What each Bus on a session has of its own: its publishers, declarations, local subscriptions, counts."""
        self._local_tokens: list[int] = []
        self._publishers: dict[str, zenoh.Publisher] = {}
        # Each key this Bus has put: whether another session hears it (put and put_if_subscribed ask).
        self._remote_matching: dict[str, RemoteMatching] = {}
        self._declared: list = []
        self._lock = threading.Lock()
        self.decode_errors = 0
        # Messages a subscriber's callback raised on, by either path (the first per key is logged with its traceback).
        self.callback_errors = 0
        self._failed_keys: set[str] = set()

    def sharing(self) -> Bus:
        """Another Bus on this one's session: services composed in one process reach each other without
        a socket. Its close() undeclares only its own entities; the session closes with this Bus."""
        shared = object.__new__(Bus)
        shared.layout = self.layout
        shared.mode = self.mode
        shared._session = self._session
        shared._owns_session = False
        shared._local = self._local
        shared._zenoh_reach = self._zenoh_reach
        shared._start_own_state()
        return shared

    @property
    def session(self) -> zenoh.Session:
        return self._session

    def peer_count(self) -> int:
        return len(list(self._session.info.peers_zid())) + len(list(self._session.info.routers_zid()))

    def put(self, key: str, message: Message, *, reliable_block: bool = True, attachment: bytes | None = None) -> None:
        """Sends a message; in a recorded run's process (publish_spool.py) it is spooled for the recording first."""
        payload = message.SerializeToString()
        spool = process_spool()
        if spool is not None:
            spool.write(key, message, payload)
        publisher = self._publisher(key, message, reliable_block)
        # Into Zenoh only when another session hears it: a put is a call that gives the interpreter's lock up and
        # takes it back, 6 us quiet and several times that in a busy process, for nothing when nobody else listens
        # (most puts where the stacks share a process).
        if self._matching_elsewhere(key, publisher).matching():
            publisher.put(payload, attachment=attachment)
        self._local.deliver(key, payload, attachment, message.DESCRIPTOR.full_name)

    def put_if_subscribed(self, key: str, message: Message) -> bool:
        """Puts only when some subscriber matches `key` (this session's own, or another session's by Zenoh's
        matching status, asked again only after Zenoh reports a change: remote_matching.py): for messages such as
        step markers that are worth nothing unheard, and the recording, which takes every message from its spool.
        True when it was sent."""
        spool = process_spool()
        recorded = spool is not None and is_recorded(key)  # not the step markers, which are many
        publisher = self._publisher(key, message, reliable_block=True)
        heard_here = bool(self._local.matching(key))
        heard_elsewhere = self._matching_elsewhere(key, publisher).matching()
        if not (recorded or heard_here or heard_elsewhere):
            return False
        payload = message.SerializeToString()  # once, for the spool and the bus
        if recorded:
            spool.write(key, message, payload)
        if heard_elsewhere:
            publisher.put(payload)
        if heard_here:
            self._local.deliver(key, payload, None, message.DESCRIPTOR.full_name)
        return heard_here or heard_elsewhere

    def _matching_elsewhere(self, key: str, publisher: zenoh.Publisher) -> RemoteMatching:
        matching = self._remote_matching.get(key)
        if matching is None:
            with self._lock:
                matching = self._remote_matching.get(key)
                if matching is None:
                    matching = self._remote_matching[key] = RemoteMatching(publisher, _direct)
                    self._declare(matching.listener)
        return matching

    def _publisher(self, key: str, message: Message, reliable_block: bool) -> zenoh.Publisher:
        publisher = self._publishers.get(key)
        if publisher is None:
            with self._lock:
                publisher = self._publishers.get(key) or self._declare_publisher(key, message, reliable_block)
        return publisher

    def publish(self, vehicle_id: str, topic: str | Topic, message: Message, attachment: bytes | None = None) -> None:
        name = topic.name if isinstance(topic, Topic) else topic
        self.put(self.layout.topic(vehicle_id, name), message, attachment=attachment)

    def _declare_publisher(self, key: str, message: Message, reliable_block: bool) -> zenoh.Publisher:
        encoding = zenoh.Encoding.APPLICATION_PROTOBUF.with_schema(message.DESCRIPTOR.full_name)
        congestion = zenoh.CongestionControl.BLOCK if reliable_block else zenoh.CongestionControl.DROP
        publisher = self._session.declare_publisher(key, encoding=encoding, congestion_control=congestion,
                                                    allowed_destination=self._zenoh_reach)
        self._publishers[key] = publisher
        return publisher

    def subscribe(self, vehicle_id: str, topic: str, callback: Callable[[Envelope], None]):
        """Subscribes to one registered topic of one vehicle ("*" for all vehicles)."""
        spec = topic_named(topic)

        def deliver(key: str, payload: bytes, attachment: bytes | None, _schema: str | None) -> None:
            envelope = self._decode(key, spec.message_type, payload, attachment)
            if envelope is not None:
                callback(envelope)

        return self._subscribe_both(self.layout.topic(vehicle_id, topic), deliver, typed_by_schema=False)

    def subscribe_key(self, key_expr: str, callback: Callable[[str, Message], None]):
        """Subscribes to any key; the message type comes from the sample's encoding schema."""

        def deliver(key: str, payload: bytes, _attachment: bytes | None, schema: str | None) -> None:
            cls = message_class(schema)
            if cls is None:
                return
            envelope = self._decode(key, cls, payload)
            if envelope is not None:
                callback(key, envelope.message)

        return self._subscribe_both(key_expr, deliver, typed_by_schema=True)

    def _subscribe_both(self, key_expr: str, deliver: Callable[[str, bytes, bytes | None, str | None], None],
                        typed_by_schema: bool):
        """deliver() gets what this session's own buses put (LocalDelivery) and, through Zenoh, what other
        sessions put; the schema is read off a sample's encoding only where the subscriber types by it."""

        def guarded(key: str, payload: bytes, attachment: bytes | None, schema: str | None) -> None:
            try:
                deliver(key, payload, attachment, schema)
            except Exception:  # the subscriber's own fault: neither the publisher nor other subscribers pay for it
                self.callback_errors += 1
                if key not in self._failed_keys:
                    self._failed_keys.add(key)
                    log.exception("a subscriber to %s failed (later failures on this key are only counted)", key)

        def on_sample(sample: zenoh.Sample) -> None:
            attachment = sample.attachment
            guarded(str(sample.key_expr), sample.payload.to_bytes(), None if attachment is None else attachment.to_bytes(),
                    _schema_of(sample.encoding) if typed_by_schema else None)

        if self._zenoh_reach is zenoh.Locality.REMOTE:
            self._local_tokens.append(self._local.subscribe(key_expr, guarded))
        return self._declare(self._session.declare_subscriber(key_expr, _direct(on_sample),
                                                              allowed_origin=self._zenoh_reach))

    def _decode(self, key: str, cls: type[Message], payload: bytes, attachment: bytes | None = None) -> Envelope | None:
        message = cls()
        try:
            message.ParseFromString(payload)
        except DecodeError as error:
            self.decode_errors += 1
            log.warning("dropped malformed %s on %s: %s", cls.DESCRIPTOR.full_name, key, error)
            return None
        vehicle_id, topic = self.layout.parse(key) or ("", key)
        return Envelope(vehicle_id, topic, message, attachment)

    def declare_token(self, key: str):
        return self._declare(self._session.liveliness().declare_token(key))

    def watch_liveliness(self, key_expr: str, on_change: Callable[[str, bool], None]):
        """Calls on_change(key, alive) for tokens present now and for every change later."""

        def on_sample(sample: zenoh.Sample) -> None:
            on_change(str(sample.key_expr), sample.kind == zenoh.SampleKind.PUT)

        return self._declare(self._session.liveliness().declare_subscriber(key_expr, on_sample, history=True))

    def alive_tokens(self, key_expr: str, timeout_s: float = 1.0) -> list[str]:
        replies = self._session.liveliness().get(key_expr, timeout=timeout_s)
        return [str(reply.ok.key_expr) for reply in replies if reply.ok is not None]

    def declare_queryable(self, key: str, answer: Callable[[], Message]):
        def on_query(query: zenoh.Query) -> None:
            with query:
                message = answer()
                encoding = zenoh.Encoding.APPLICATION_PROTOBUF.with_schema(message.DESCRIPTOR.full_name)
                query.reply(key, message.SerializeToString(), encoding=encoding)

        return self._declare(self._session.declare_queryable(key, on_query))

    def query(self, key_expr: str, cls: type[Message], timeout_s: float = 2.0) -> list[Message]:
        results = []
        for reply in self._session.get(key_expr, timeout=timeout_s):
            if reply.ok is None:
                continue
            message = cls()
            try:
                message.ParseFromString(reply.ok.payload.to_bytes())
            except DecodeError:
                continue
            results.append(message)
        return results

    def _declare(self, entity):
        self._declared.append(entity)
        return entity

    def close(self) -> None:
        for token in self._local_tokens:
            self._local.unsubscribe(token)
        self._local_tokens.clear()
        for entity in reversed(self._declared):
            try:
                entity.undeclare()
            except Exception:  # already gone with a closing session
                pass
        self._declared.clear()
        for publisher in self._publishers.values():
            try:
                publisher.undeclare()
            except Exception:
                pass
        self._publishers.clear()
        if self._owns_session and not self._session.is_closed():
            self._session.close()


def _open(config: zenoh.Config) -> zenoh.Session:
    """A session; when it cannot open and its TLS credentials say why, BusCredentialsError saying so in one line."""
    try:
        return zenoh.open(config)
    except zenoh.ZError:
        from coopdrive.bus.credential_check import credentials_problem  # X.509 only when a session did not open

        problem = credentials_problem(config)
        if problem is None:
            raise
        raise BusCredentialsError(problem) from None


def _check_required_mode(mode: str) -> None:
    """BusCredentialsError when the process must be on an authenticated bus (REQUIRED_MODE_VARIABLE) and is not."""
    required = os.environ.get(REQUIRED_MODE_VARIABLE)
    if required == MTLS and mode != MTLS:
        raise BusCredentialsError(f"this vehicle's bus takes only authenticated sessions ({REQUIRED_MODE_VARIABLE}="
                                  f"{required}) and this one has no credentials (--zenoh-config): {REMEDY}")


def _direct(callback: Callable[[Any], None]) -> zenoh.handlers.Callback:
    """Runs the callback (of a subscriber's samples, or of a matching listener's reports) on Zenoh's thread instead
    of handing it to a Python thread first.

    Saves a thread switch per message and keeps the wire order across subscribers of one link.
    Our callbacks only decode and enqueue, so they never hold the receive thread up.
    """
    return zenoh.handlers.Callback(callback, indirect=False)


def _schema_of(encoding: zenoh.Encoding) -> str | None:
    """The schema part of "application/protobuf;<type name>"."""
    text = str(encoding)
    return text.split(";", 1)[1] if ";" in text else None
