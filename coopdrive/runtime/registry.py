"""Which class implements each service name used by `coopdrive service NAME` and compose (from the services table)."""

from __future__ import annotations

import importlib

from coopdrive.bus.services import SERVICES, VEHICLE_STACK, service_entry
from coopdrive.runtime.service import Service

SERVICE_CLASSES: dict[str, str] = {entry.name: entry.implementation for entry in SERVICES}

__all__ = ["SERVICE_CLASSES", "VEHICLE_STACK", "service_class"]


def service_class(name: str) -> type[Service]:
    module_name, _, class_name = service_entry(name).implementation.partition(":")
    return getattr(importlib.import_module(module_name), class_name)
