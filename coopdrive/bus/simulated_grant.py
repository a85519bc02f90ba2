"""What a simulated vehicle's bus adds to the grants (`coopdrive pki bus DIR --vehicle ID --simulated`): the desk
runs the vehicle's stack against the simulator, on the same authenticated bus as the car.

- The simulator gets a certificate of its own (common name "sim"): it puts the world's topics (under the world's id,
  with its lockstep clocks) and, in the car's place, the topics it declares it publishes under the vehicle (GNSS
  fixes, the CAN bus, the sensors); it reads what it declares it reads of the vehicle (CAN commands, radio frames).
- Every service also hears the world (its clock, ground truth, results) and the lockstep's step markers: it puts a
  marker for each topic it publishes ("@step/<topic>", coopdrive.runtime.stepping) and hears those of each topic it
  reads. Markers and clocks are verbatim chunks ("@step", "@clock") that a "**" does not match: named here one by one.
"""

from __future__ import annotations

from dataclasses import replace

from coopdrive.bus.bus_grant import BusGrant, bus_services, observer_grant, service_grant
from coopdrive.bus.keys import WORLD_ID, KeyLayout
from coopdrive.bus.services import SERVICES, WORLD_SERVICE, ServiceEntry
from coopdrive.bus.topic import EVERY_OTHER_TOPIC
from coopdrive.bus.topics import declarations_of, diagnostics_topic, published_by, topic_registry

WORLD_ONLY_TOPICS = ("clock", "ground_truth", "result", "service_fault")


def world_keys(layout: KeyLayout) -> tuple[str, ...]:
    """What everyone on a simulated bus hears of the world: its topics and its lockstep clocks and markers."""
    return (layout.all_topics(WORLD_ID), f"{layout.root}/{WORLD_ID}/@clock/**", layout.step_done(WORLD_ID, "**"))


def simulated_service_grant(entry: ServiceEntry, vehicle_id: str, layout: KeyLayout | None = None) -> BusGrant:
    """`entry`'s grant on the vehicle, with the world and the markers of its topics."""
    layout = layout or KeyLayout()
    grant = service_grant(entry, vehicle_id, layout)
    read = declarations_of(entry).SUBSCRIBES
    read_names = ([topic for topic in topic_registry() if topic not in _own(entry)] if EVERY_OTHER_TOPIC in read
                  else sorted(read))
    return replace(grant,
                   puts=grant.puts + tuple(layout.step_done(vehicle_id, topic) for topic in _own(entry)),
                   subscriptions=grant.subscriptions + world_keys(layout)
                   + tuple(layout.step_done(vehicle_id, topic) for topic in read_names))


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


def heard_on_a_simulated_bus(vehicle_id: str, layout: KeyLayout | None = None) -> tuple[str, ...]:
    """Besides the vehicle's topics, whose subscribers every publisher may learn of: the step markers and the world
    (a lockstep publisher puts a marker only when someone hears it)."""
    layout = layout or KeyLayout()
    return (layout.step_done(vehicle_id, "**"),) + world_keys(layout)


def _own(entry: ServiceEntry) -> list[str]:
    return [topic.name for topic in published_by(entry)] + [diagnostics_topic(entry.name).name]
