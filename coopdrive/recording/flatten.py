"""A protobuf message as one flat row: dotted field names, enum names as text, repeated fields as JSON text.

Every field is present, set or not (proto3 gives defaults), so all rows of one message type have the same
columns; map fields are the exception, one column per key (`counters.handler_errors`). Repeated fields stay
one column holding JSON (a list of numbers, or of objects for repeated messages): their length varies from
message to message, and pandas reads the column back with json.loads.
"""

from __future__ import annotations

import json
from typing import Any

from google.protobuf.descriptor import FieldDescriptor
from google.protobuf.json_format import MessageToDict
from google.protobuf.message import Message

# Deeper than any coopdrive message; stops a self-referencing type.
MAX_DEPTH = 8


def flatten(message: Message, prefix: str = "", depth: int = 0) -> dict[str, Any]:
    row: dict[str, Any] = {}
    for field in message.DESCRIPTOR.fields:
        name = f"{prefix}{field.name}"
        value = getattr(message, field.name)
        if _is_map(field):
            row.update({f"{name}.{key}": _scalar(field.message_type.fields_by_name["value"], item)
                        for key, item in sorted(value.items())})
        elif field.is_repeated:
            row[name] = json.dumps([_plain(field, item) for item in value])
        elif field.type == FieldDescriptor.TYPE_MESSAGE:
            if depth < MAX_DEPTH:
                row.update(flatten(value, f"{name}.", depth + 1))
        else:
            row[name] = _scalar(field, value)
    return row


def _is_map(field: FieldDescriptor) -> bool:
    return (field.type == FieldDescriptor.TYPE_MESSAGE and field.message_type.GetOptions().map_entry)


def _scalar(field: FieldDescriptor, value: Any) -> Any:
    if field.type == FieldDescriptor.TYPE_ENUM:
        described = field.enum_type.values_by_number.get(value)
        return described.name if described is not None else value
    if field.type == FieldDescriptor.TYPE_BYTES:
        return value.hex()
    return value


def _plain(field: FieldDescriptor, item: Any) -> Any:
    if field.type == FieldDescriptor.TYPE_MESSAGE:
        return MessageToDict(item, preserving_proto_field_name=True)
    return _scalar(field, item)


def numeric_fields(row: dict[str, Any]) -> dict[str, float]:
    """The fields of a flat row that are numbers (bools and enum names left out)."""
    return {key: float(value) for key, value in row.items()
            if isinstance(value, (int, float)) and not isinstance(value, bool)}
