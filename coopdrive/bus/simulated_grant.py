"""What a simulated vehicle's bus adds to the grants (`coopdrive pki bus DIR --vehicle ID --simulated`): the desk
runs the vehicle's stack against the simulator, on the same authenticated bus as the car.

- The simulator gets a certificate of its own (common name "sim"): it puts the world's topics (under the world's id,
  with its lockstep clocks) and, in the car's place, the topics it declares it publishes under the vehicle (GNSS
  fixes, the CAN bus, the sensors); it reads what it declares it reads of the vehicle (CAN commands, radio frames).
- Every service (and observer) also hears the world: its topics, its lockstep clocks and markers. Those are verbatim
  chunks ("@clock", "@step") that a "**" does not match: named one by one. (The step markers of the vehicle's own
  topics are in every service's grant: coopdrive.bus.bus_grant.)
"""

from __future__ import annotations

from dataclasses import replace

from coopdrive.bus.bus_grant import BusGrant, bus_services, observer_grant, service_grant
from coopdrive.bus.keys import WORLD_ID, KeyLayout
from coopdrive.bus.services import SERVICES, WORLD_SERVICE, ServiceEntry
from coopdrive.bus.topics import declarations_of, published_by

WORLD_ONLY_TOPICS = ("clock", "ground_truth", "result", "service_fault")


def world_keys(layout: KeyLayout) -> tuple[str, ...]:
    """What everyone on a simulated bus hears of the world: its topics and its lockstep clocks and markers."""
    return (layout.all_topics(WORLD_ID), f"{layout.root}/{WORLD_ID}/@clock/**", layout.step_done(WORLD_ID, "**"))


def simulated_service_grant(entry: ServiceEntry, vehicle_id: str, layout: KeyLayout | None = None) -> BusGrant:
    """`entry`'s grant on the vehicle (with the markers of its topics), and the world."""
    layout = layout or KeyLayout()
    grant = service_grant(entry, vehicle_id, layout)
    return replace(grant, subscriptions=grant.subscriptions + world_keys(layout))


def world_grant(vehicle_id: str, layout: KeyLayout | None = None) -> BusGrant:
    """The simulator's grant on a simulated vehicle's bus."""
    layout = layout or KeyLayout()
    entry = next(entry for entry in SERVICES if entry.name == WORLD_SERVICE)
    on_vehicle = [topic.name for topic in published_by(entry) if topic.name not in WORLD_ONLY_TOPICS]
    read = sorted(declarations_of(entry).SUBSCRIBES)
    return BusGrant(
        subject=WORLD_SERVICE,
        puts=(layout.all_topics(WORLD_ID), f"{layout.root}/{WORLD_ID}/@clock/**", layout.step_done(WORLD_ID, "**"))
        + tuple(layout.topic(vehicle_id, topic) for topic in on_vehicle)
        + tuple(layout.step_done(vehicle_id, topic) for topic in on_vehicle),
        subscriptions=tuple(layout.topic(vehicle_id, topic) for topic in read)
        + tuple(layout.step_done(vehicle_id, topic) for topic in read) + world_keys(layout),
        tokens=(layout.liveliness(WORLD_ID, WORLD_SERVICE),),
        queryables=(layout.service_info(WORLD_ID, WORLD_SERVICE),),
        queries=())


def simulated_grants(vehicle_id: str, observers: tuple[str, ...] = (),
                     layout: KeyLayout | None = None) -> list[BusGrant]:
    """The simulator's grant, every service's with the world and its markers, then each observer's with the world."""
    layout = layout or KeyLayout()
    if len(set(observers)) != len(observers):
        raise ValueError(f"an observer is named twice: {', '.join(observers)}")
    observing = [observer_grant(name, vehicle_id, layout) for name in observers]
    return ([world_grant(vehicle_id, layout)]
            + [simulated_service_grant(entry, vehicle_id, layout) for entry in bus_services()]
            + [replace(grant, subscriptions=grant.subscriptions + world_keys(layout)) for grant in observing])


def heard_on_a_simulated_bus(layout: KeyLayout | None = None) -> tuple[str, ...]:
    """Besides the vehicle's topics and markers, whose subscribers every publisher may learn of: the world's."""
    return world_keys(layout or KeyLayout())
