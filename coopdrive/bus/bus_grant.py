"""What one certificate holder may do on a vehicle's bus, as key expressions, derived from the services table.

A service may put exactly the topics its declaration (services/<name>/topics.py) says it publishes, and subscribe to
those it says it reads, all under its own vehicle (and the simulator's topics it puts in the simulator's place on
a vehicle: PUBLISHES_ON_VEHICLE, as actuation puts the car's CAN frames on can/vehicle); the gateway's declaration names only its command topics, so that
is all it may put. An observer only subscribes. Besides its topics, every service has what the runtime gives each
one (coopdrive.runtime.runner): its diagnostics topic, its liveliness token and its info queryable. Anything not
granted here is denied by the router (coopdrive.bus.router_access).

Adding a topic to a declaration adds it here: nothing is listed twice by hand.
"""

from __future__ import annotations

import re
from dataclasses import dataclass

from coopdrive.bus.keys import KeyLayout
from coopdrive.bus.services import SERVICES, WORLD_SERVICE, ServiceEntry
from coopdrive.bus.topic import EVERY_OTHER_TOPIC
from coopdrive.bus.topics import declarations_of, diagnostics_topic, published_by, topic_named, topic_registry

# A vehicle id and an observer's name are one chunk of a key expression and a file name: no "/", no wildcards.
NAME_PATTERN = re.compile(r"[A-Za-z0-9][A-Za-z0-9_.-]*")
# Common names the command gives itself: no observer may take one of them (nor a service's name).
ROUTER_NAME = "router"
AUTHORITY_NAME = "ca"


@dataclass(frozen=True)
class BusGrant:
    # The certificate's common name, which the router's access control matches.
    subject: str
    # Key expressions it may put on.
    puts: tuple[str, ...]
    # Key expressions it may declare subscribers on (and receive the puts of).
    subscriptions: tuple[str, ...]
    # Liveliness tokens it may declare.
    tokens: tuple[str, ...]
    # Queryables it may declare (and answer the queries of).
    queryables: tuple[str, ...]
    # Key expressions it may query (the services' info).
    queries: tuple[str, ...]


def checked_name(kind: str, name: str) -> str:
    """`name` if it can stand as one chunk of a key and as a file name; ValueError saying what is wrong otherwise."""
    if not NAME_PATTERN.fullmatch(name):
        raise ValueError(f"{kind} {name!r} must be letters, digits, '_', '-' or '.', starting with a letter or digit")
    return name


def bus_services() -> tuple[ServiceEntry, ...]:
    """The services that get a certificate: every one of the table but the simulator (there is no world on a car)."""
    return tuple(entry for entry in SERVICES if entry.name != WORLD_SERVICE)


def service_grant(entry: ServiceEntry, vehicle_id: str, layout: KeyLayout | None = None) -> BusGrant:
    """What service `entry` may do on vehicle `vehicle_id`'s bus, read off its declaration."""
    layout = layout or KeyLayout()
    checked_name("vehicle id", vehicle_id)
    published = ([topic.name for topic in published_by(entry)] + [diagnostics_topic(entry.name).name]
                 + list(stands_in_for_the_world(entry)))
    read = declarations_of(entry).SUBSCRIBES
    read_names = ([name for name in topic_registry() if name not in published] if EVERY_OTHER_TOPIC in read
                  else sorted(read))
    subscriptions = ((layout.all_topics(vehicle_id),) if EVERY_OTHER_TOPIC in read
                     else tuple(layout.topic(vehicle_id, name) for name in read_names))
    # The runtime's step markers ("@step/<topic>", which "**" does not match): a service puts those of its topics and
    # listens for those of what it reads (only a lockstep run sends any; the listening is declared in every run).
    return BusGrant(subject=entry.name,
                    puts=tuple(layout.topic(vehicle_id, name) for name in published)
                    + tuple(layout.step_done(vehicle_id, name) for name in published),
                    subscriptions=subscriptions + tuple(layout.step_done(vehicle_id, name) for name in read_names),
                    tokens=(layout.liveliness(vehicle_id, entry.name),),
                    queryables=(layout.service_info(vehicle_id, entry.name),),
                    queries=())


def stands_in_for_the_world(entry: ServiceEntry) -> tuple[str, ...]:
    """The simulator's topics the service puts on a vehicle in its place (its declaration's PUBLISHES_ON_VEHICLE);
    ValueError for one the simulator does not publish."""
    names = tuple(getattr(declarations_of(entry), "PUBLISHES_ON_VEHICLE", ()))
    strays = [name for name in names if topic_named(name).publisher != WORLD_SERVICE]
    if strays:
        raise ValueError(f"{entry.declarations} stands in on a vehicle for topics the {WORLD_SERVICE} service does not "
                         f"publish: {', '.join(strays)}")
    return names


def observer_grant(name: str, vehicle_id: str, layout: KeyLayout | None = None) -> BusGrant:
    """An observer (a team laptop, a recorder, the Foxglove bridge): subscribes to every topic of the vehicle and asks
    the services' info; puts nothing, declares nothing but its presence (a liveliness token of its name, which
    healthchecks look for)."""
    layout = layout or KeyLayout()
    checked_name("vehicle id", vehicle_id)
    taken = {entry.name for entry in SERVICES} | {ROUTER_NAME, AUTHORITY_NAME}
    if checked_name("observer name", name) in taken:
        raise ValueError(f"observer name {name!r} is taken (by a service or the bus itself): "
                         f"choose another than {', '.join(sorted(taken))}")
    return BusGrant(subject=name, puts=(), subscriptions=(layout.all_topics(vehicle_id),),
                    tokens=(layout.liveliness(vehicle_id, name),), queryables=(),
                    queries=(layout.service_info(vehicle_id, "*"),))


def bus_grants(vehicle_id: str, observers: tuple[str, ...] = (), layout: KeyLayout | None = None) -> list[BusGrant]:
    """Every service's grant (the services table's order), then each observer's."""
    if len(set(observers)) != len(observers):
        raise ValueError(f"an observer is named twice: {', '.join(observers)}")
    return ([service_grant(entry, vehicle_id, layout) for entry in bus_services()]
            + [observer_grant(name, vehicle_id, layout) for name in observers])
