"""The topic registry: which message each topic carries and which service publishes it, built from the services
table and each service's own declaration of what it publishes.

One publisher service per topic and vehicle is what lets the lockstep barrier order data flow
(see coopdrive.runtime.dispatcher).

The declaration modules are imported on first use, not when this module is: a declaration imports
coopdrive.bus.topic, so reading the declarations while coopdrive.bus is still being imported would be circular.
`TOPICS` stays a module attribute (PEP 562 __getattr__) for its existing readers.
"""

from __future__ import annotations

import importlib
from functools import cache
from types import ModuleType

from coopdrive.bus.services import SERVICES, ServiceEntry
from coopdrive.bus.topic import Topic
from coopdrive.v1 import diagnostics_pb2

__all__ = ["TOPICS", "Topic", "declarations_of", "diagnostics_topic", "published_by", "stepped_topics_of", "topic_named",
           "topic_registry"]


def declarations_of(entry: ServiceEntry) -> ModuleType:
    """The service's declaration module (PUBLISHES, SUBSCRIBES)."""
    return importlib.import_module(entry.declarations)


def diagnostics_topic(service: str) -> Topic:
    """The runtime publishes every service's counters here (coopdrive.runtime.runner), so no service declares it."""
    return Topic(f"diagnostics/{service}", diagnostics_pb2.Diagnostics, service, stepped=False)


def published_by(entry: ServiceEntry) -> tuple[Topic, ...]:
    """The topics the service declares it publishes (without its diagnostics)."""
    topics = tuple(declarations_of(entry).PUBLISHES)
    strays = [topic.name for topic in topics if topic.publisher != entry.name]
    if strays:
        raise ValueError(f"{entry.declarations} declares topics of another publisher: {', '.join(strays)}")
    return topics


@cache
def topic_registry() -> dict[str, Topic]:
    """Every topic by name, in the services table's order: each service's declared topics, then the diagnostics."""
    every = [topic for entry in SERVICES for topic in published_by(entry)]
    every += [diagnostics_topic(entry.name) for entry in SERVICES]
    registry = {topic.name: topic for topic in every}
    if len(registry) != len(every):
        names = [topic.name for topic in every]
        raise ValueError(f"topics declared twice: {sorted({n for n in names if names.count(n) > 1})}")
    return registry


def __getattr__(name: str):
    if name == "TOPICS":
        return topic_registry()
    raise AttributeError(f"module {__name__!r} has no attribute {name!r}")


def stepped_topics_of(service: str) -> list[str]:
    """The stepped topics `service` publishes, sorted."""
    return sorted(topic.name for topic in topic_registry().values() if topic.publisher == service and topic.stepped)


def topic_named(name: str) -> Topic:
    registry = topic_registry()
    try:
        return registry[name]
    except KeyError:
        raise KeyError(f"unknown topic {name!r}; known topics: {', '.join(sorted(registry))}") from None
