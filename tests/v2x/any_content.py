"""A hypothesis strategy for arbitrary protobuf messages: every field may hold any value its type allows.

Doubles include NaN, infinities and huge values; enums include numbers the enum does not name (proto3
enums are open); optional fields and sub-messages may be absent; repeated fields hold up to three items.
"""

from __future__ import annotations

from google.protobuf.descriptor import FieldDescriptor
from google.protobuf.message import Message
from hypothesis import strategies as st

_INT_RANGES = {
    FieldDescriptor.TYPE_INT32: (-2**31, 2**31 - 1), FieldDescriptor.TYPE_SINT32: (-2**31, 2**31 - 1),
    FieldDescriptor.TYPE_SFIXED32: (-2**31, 2**31 - 1), FieldDescriptor.TYPE_UINT32: (0, 2**32 - 1),
    FieldDescriptor.TYPE_FIXED32: (0, 2**32 - 1), FieldDescriptor.TYPE_INT64: (-2**63, 2**63 - 1),
    FieldDescriptor.TYPE_SINT64: (-2**63, 2**63 - 1), FieldDescriptor.TYPE_SFIXED64: (-2**63, 2**63 - 1),
    FieldDescriptor.TYPE_UINT64: (0, 2**64 - 1), FieldDescriptor.TYPE_FIXED64: (0, 2**64 - 1),
}


def _scalar(field: FieldDescriptor) -> st.SearchStrategy:
    if field.type == FieldDescriptor.TYPE_DOUBLE:
        return st.one_of(st.floats(-1e3, 1e3), st.floats())
    if field.type == FieldDescriptor.TYPE_FLOAT:
        return st.floats(width=32)
    if field.type == FieldDescriptor.TYPE_BOOL:
        return st.booleans()
    if field.type == FieldDescriptor.TYPE_ENUM:
        named = [value.number for value in field.enum_type.values]
        return st.one_of(st.sampled_from(named), st.integers(-2**31, 2**31 - 1))
    if field.type == FieldDescriptor.TYPE_STRING:
        return st.text(max_size=8)
    if field.type == FieldDescriptor.TYPE_BYTES:
        return st.binary(max_size=8)
    low, high = _INT_RANGES[field.type]
    return st.one_of(st.integers(0, 100), st.integers(low, high))


@st.composite
def _fill(draw: st.DrawFn, message_class: type[Message], skip: frozenset[str], depth: int) -> Message:
    message = message_class()
    for field in message_class.DESCRIPTOR.fields:
        if field.name in skip:
            continue
        if field.type == FieldDescriptor.TYPE_MESSAGE:
            if depth >= 3 or not draw(st.booleans()):
                continue
            if field.is_repeated:
                container = getattr(message, field.name)
                for _ in range(draw(st.integers(0, 3))):
                    item = container.add()
                    item.CopyFrom(draw(_fill(type(item), skip, depth + 1)))
            else:
                sub_message = getattr(message, field.name)
                sub_message.CopyFrom(draw(_fill(type(sub_message), skip, depth + 1)))
        elif field.is_repeated:
            getattr(message, field.name).extend(draw(st.lists(_scalar(field), max_size=3)))
        elif not field.has_presence or draw(st.booleans()):
            setattr(message, field.name, draw(_scalar(field)))
    return message


def any_message(message_class: type[Message], skip: frozenset[str] = frozenset({"header"})) -> st.SearchStrategy:
    """Arbitrary instances of message_class; fields named in skip stay unset at every depth."""
    return _fill(message_class, skip, 0)
