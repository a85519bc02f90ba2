"""Finds the generated protobuf class of a full type name such as "coopdrive.v1.EgoState"."""

import importlib
import pkgutil
from functools import cache

from google.protobuf.message import Message

import coopdrive.v1


@cache
def _all_classes() -> dict[str, type[Message]]:
    classes: dict[str, type[Message]] = {}
    for module_info in pkgutil.iter_modules(coopdrive.v1.__path__):
        if not module_info.name.endswith("_pb2"):
            continue
        module = importlib.import_module(f"coopdrive.v1.{module_info.name}")
        for name in module.DESCRIPTOR.message_types_by_name:
            cls = getattr(module, name)
            classes[cls.DESCRIPTOR.full_name] = cls
    return classes


def message_class(full_name: str | None) -> type[Message] | None:
    if not full_name:
        return None
    return _all_classes().get(full_name)


def all_message_classes() -> dict[str, type[Message]]:
    return dict(_all_classes())
