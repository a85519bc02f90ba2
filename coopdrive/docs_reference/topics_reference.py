"""The topics and messages reference: every topic of the services table's declarations (services/<name>/topics.py)
with its message, publisher and readers, then every coopdrive.v1 message and enum those messages use, with their
fields from the protobuf descriptors and their comments from proto/."""

from __future__ import annotations

from google.protobuf.descriptor import Descriptor, EnumDescriptor, FieldDescriptor

from coopdrive.docs_reference.markdown_table import cell, code, table
from coopdrive.docs_reference.proto_comments import comment_of

PACKAGE = "coopdrive.v1"

SCALAR_NAMES = {getattr(FieldDescriptor, name): name[len("TYPE_"):].lower()
                for name in dir(FieldDescriptor) if name.startswith("TYPE_")}

INTRO = """# Topics and messages

Generated from the services table (`coopdrive/bus/services.py`), each service's topic declaration
(`services/<name>/topics.py`) and the protobuf descriptors when the documentation is built. Every topic's key is
`coopdrive/<vehicle>/<topic>`; the simulator's world topics use the vehicle id `world`. Each service also
publishes `diagnostics/<service>` (its counters, once a second), and the gateway reads every topic.
[Architecture](../architecture.md) draws the same table as a graph.
"""


def _anchor(full_name: str) -> str:
    """The id Python-Markdown's toc gives the heading `` `coopdrive.v1.Name` ``."""
    return full_name.lower().replace(".", "")


def _link(full_name: str) -> str:
    return f"[`{full_name.rsplit('.', 1)[-1]}`](#{_anchor(full_name)})"


def topics_table() -> str:
    from coopdrive.bus.architecture import subscribers_of
    from coopdrive.bus.topics import topic_registry

    rows = [[code(topic.name), _link(topic.type_name), code(topic.publisher),
             ", ".join(code(reader) for reader in subscribers_of(topic)), "yes" if topic.stepped else "no"]
            for topic in topic_registry().values()]
    return table(["topic", "message", "published by", "read by", "lockstep waits for it"], rows)


def _field_type(field: FieldDescriptor) -> str:
    if field.message_type is not None and field.message_type.GetOptions().map_entry:
        key, value = field.message_type.fields_by_name["key"], field.message_type.fields_by_name["value"]
        return f"map of {_field_type(key)} to {_field_type(value)}"
    if field.message_type is not None:
        kind = _link(field.message_type.full_name) if _ours(field.message_type) else code(field.message_type.full_name)
    elif field.enum_type is not None:
        kind = _link(field.enum_type.full_name) if _ours(field.enum_type) else code(field.enum_type.full_name)
    else:
        kind = SCALAR_NAMES[field.type]
    return f"repeated {kind}" if field.is_repeated else kind


def _ours(descriptor) -> bool:
    return descriptor.full_name.startswith(PACKAGE + ".")


def _referenced(descriptor: Descriptor) -> list:
    """The coopdrive.v1 messages and enums the message's fields use (a map's value type for a map)."""
    found = []
    for field in descriptor.fields:
        target = field.message_type or field.enum_type
        if target is not None and field.message_type is not None and field.message_type.GetOptions().map_entry:
            value = field.message_type.fields_by_name["value"]
            target = value.message_type or value.enum_type
        if target is not None and _ours(target):
            found.append(target)
    return found


def reachable(roots: list[Descriptor]) -> list:
    """The messages and enums reachable from `roots`, breadth first, each once."""
    seen: dict[str, object] = {}
    queue = list(roots)
    while queue:
        descriptor = queue.pop(0)
        if descriptor.full_name in seen:
            continue
        seen[descriptor.full_name] = descriptor
        if isinstance(descriptor, Descriptor):
            queue += _referenced(descriptor)
    return list(seen.values())


def descriptor_markdown(descriptor) -> str:
    parts = [f"### `{descriptor.full_name}`", ""]
    if isinstance(descriptor, EnumDescriptor):
        rows = [[code(value.name), str(value.number), cell(comment_of(descriptor, value.name))]
                for value in descriptor.values]
        parts.append(table(["value", "number", "what it is"], rows))
    else:
        rows = [[code(field.name), _field_type(field), str(field.number), cell(comment_of(descriptor, field.name))]
                for field in descriptor.fields]
        parts.append(table(["field", "type", "number", "what it is"], rows) if rows else "(no fields)")
    return "\n".join(parts + [""])


def topics_markdown() -> str:
    from coopdrive.bus.topics import topic_registry

    roots = [topic.message_type.DESCRIPTOR for topic in topic_registry().values()]
    messages = [descriptor_markdown(d) for d in reachable(roots)]
    return "\n".join([INTRO, "## Topics", "", topics_table(), "", "## Messages", "", *messages])
