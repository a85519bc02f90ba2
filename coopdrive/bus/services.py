"""The one table of coopdrive's services: each name, the class that implements it, the module that declares the
topics it publishes, and its place in a step.

The registry (`coopdrive service NAME`), the topic registry (coopdrive.bus.topics), the lockstep pipeline order
and docs/architecture.md are all built from this table. Implementations and declarations are named, not imported:
the framework never imports a service's code, and reads a declaration module (which imports only protobuf
messages) the first time it needs a topic.
"""

from __future__ import annotations

from dataclasses import dataclass


@dataclass(frozen=True)
class ServiceEntry:
    name: str
    # "module:Class", imported only when the service is started.
    implementation: str
    # "module" whose PUBLISHES (the Topics the service publishes) and SUBSCRIBES (the topic names it reads) the
    # topic registry and the architecture page are built from.
    declarations: str
    # Within a lockstep step a service sees what lower ranks published in the same step, and higher ranks'
    # messages of the step before (their feedback): sensor -> estimate -> decision -> command.
    pipeline_rank: int
    # Runs once for every stack vehicle (the simulator and the gateway run once per run or per vehicle's desk).
    in_vehicle_stack: bool
    # Takes part in the lockstep barrier; the gateway only observes.
    lockstep: bool = True


SERVICES: tuple[ServiceEntry, ...] = (
    # The service that owns the world (simulated time, sensors, radio): first in every step.
    ServiceEntry("sim", "coopdrive.services.sim.service:SimService", "coopdrive.services.sim.topics",
                 0, in_vehicle_stack=False),
    ServiceEntry("geolocation", "coopdrive.services.geolocation.service:GeolocationService",
                 "coopdrive.services.geolocation.topics", 10, True),
    ServiceEntry("v2x", "coopdrive.services.v2x.service:V2xService", "coopdrive.services.v2x.topics", 20, True),
    ServiceEntry("scene", "coopdrive.services.scene.service:SceneService", "coopdrive.services.scene.topics",
                 30, True),
    ServiceEntry("planner", "coopdrive.services.planner.service:PlannerService",
                 "coopdrive.services.planner.topics", 40, True),
    ServiceEntry("control", "coopdrive.services.control.service:ControlService",
                 "coopdrive.services.control.topics", 50, True),
    ServiceEntry("actuation", "coopdrive.services.actuation.service:ActuationService",
                 "coopdrive.services.actuation.topics", 60, True),
    ServiceEntry("gateway", "coopdrive.services.gateway.service:GatewayService",
                 "coopdrive.services.gateway.topics", 90, False, lockstep=False),
)

SERVICE_NAMES = tuple(entry.name for entry in SERVICES)
WORLD_SERVICE = SERVICES[0].name
# The services of one vehicle's stack, in pipeline order.
VEHICLE_STACK = tuple(entry.name for entry in sorted(SERVICES, key=lambda e: e.pipeline_rank) if entry.in_vehicle_stack)


def service_entry(name: str) -> ServiceEntry:
    for entry in SERVICES:
        if entry.name == name:
            return entry
    raise KeyError(f"unknown service {name!r}; known: {', '.join(SERVICE_NAMES)}")
