"""Which class implements each service name used by `coopdrive service NAME` and compose."""

from __future__ import annotations

import importlib

from coopdrive.runtime.service import Service

SERVICE_CLASSES: dict[str, str] = {
    "sim": "coopdrive.services.sim.service:SimService",
    "geolocation": "coopdrive.services.geolocation.service:GeolocationService",
    "v2x": "coopdrive.services.v2x.service:V2xService",
    "scene": "coopdrive.services.scene.service:SceneService",
    "planner": "coopdrive.services.planner.service:PlannerService",
    "control": "coopdrive.services.control.service:ControlService",
    "actuation": "coopdrive.services.actuation.service:ActuationService",
    "gateway": "coopdrive.services.gateway.service:GatewayService",
}

# The services of one vehicle's stack in the follow loop, in pipeline order.
VEHICLE_STACK = ("geolocation", "scene", "planner", "control", "actuation")


def service_class(name: str) -> type[Service]:
    try:
        target = SERVICE_CLASSES[name]
    except KeyError:
        raise KeyError(f"unknown service {name!r}; known: {', '.join(SERVICE_CLASSES)}") from None
    module_name, _, class_name = target.partition(":")
    return getattr(importlib.import_module(module_name), class_name)
