"""Typed publish/subscribe of coopdrive.v1 protobuf messages over Eclipse Zenoh."""

from coopdrive.bus.keys import KeyLayout
from coopdrive.bus.session import Bus, BusConfig, Envelope
from coopdrive.bus.topic import Topic
from coopdrive.bus.topics import topic_named, topic_registry

__all__ = ["Bus", "BusConfig", "Envelope", "KeyLayout", "TOPICS", "Topic", "topic_named"]


def __getattr__(name: str):
    # The registry reads the services' declarations on first use (see coopdrive.bus.topics).
    if name == "TOPICS":
        return topic_registry()
    raise AttributeError(f"module {__name__!r} has no attribute {name!r}")
