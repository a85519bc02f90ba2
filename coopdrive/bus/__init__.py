"""Typed publish/subscribe of coopdrive.v1 protobuf messages over Eclipse Zenoh."""

from coopdrive.bus.keys import KeyLayout
from coopdrive.bus.session import Bus, BusConfig, Envelope
from coopdrive.bus.topics import TOPICS, Topic, topic_named

__all__ = ["Bus", "BusConfig", "Envelope", "KeyLayout", "TOPICS", "Topic", "topic_named"]
