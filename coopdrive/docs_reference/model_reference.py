"""A pydantic model as reference tables: every key with its type, default and description, nested models flattened
into dotted keys (`geolocator.jerk_std_mps3`, as `--set` takes them), lists of models as `key[].field`, and each
variant of a tagged union (a scenario's faults) as a section of its own."""

from __future__ import annotations

import enum
import math
import types
import typing
from dataclasses import dataclass, field

from pydantic import BaseModel
from pydantic_core import PydanticUndefined

from coopdrive.docs_reference.field_comments import field_description
from coopdrive.docs_reference.markdown_table import cell, code, table

REQUIRED = "required"


@dataclass(frozen=True)
class Row:
    key: str
    type: str
    default: str
    description: str


@dataclass
class Section:
    title: str
    description: str
    rows: list[Row] = field(default_factory=list)


def _without_none(annotation) -> tuple[object, bool]:
    """(the annotation without None, whether None was allowed)."""
    if typing.get_origin(annotation) in (typing.Union, types.UnionType):
        args = [a for a in typing.get_args(annotation) if a is not type(None)]
        optional = len(args) < len(typing.get_args(annotation))
        return (args[0] if len(args) == 1 else typing.Union[tuple(args)]), optional
    return annotation, False


def _unannotated(annotation):
    return typing.get_args(annotation)[0] if typing.get_origin(annotation) is typing.Annotated else annotation


def _is_model(annotation) -> bool:
    return isinstance(annotation, type) and issubclass(annotation, BaseModel)


def _union_models(annotation) -> list[type[BaseModel]]:
    """The models of a union of models (a tagged union), else []."""
    annotation = _unannotated(annotation)
    if typing.get_origin(annotation) not in (typing.Union, types.UnionType):
        return []
    members = [_unannotated(a) for a in typing.get_args(annotation)]
    return members if members and all(_is_model(m) for m in members) else []


def _tag(model: type[BaseModel]) -> tuple[str, str]:
    """(field, value) of the Literal field that tells this variant of a tagged union apart."""
    for name, info in model.model_fields.items():
        if typing.get_origin(info.annotation) is typing.Literal and len(typing.get_args(info.annotation)) == 1:
            return name, str(typing.get_args(info.annotation)[0])
    return "", model.__name__


def type_text(annotation) -> str:
    annotation = _unannotated(annotation)
    inner, optional = _without_none(annotation)
    text = _plain_type_text(inner)
    return f"{text} or none" if optional else text


def _plain_type_text(annotation) -> str:
    origin, args = typing.get_origin(annotation), typing.get_args(annotation)
    if origin is typing.Literal:
        return "one of " + ", ".join(str(a) for a in args)
    if isinstance(annotation, type) and issubclass(annotation, enum.Enum):
        return "one of " + ", ".join(str(m.value) for m in annotation)
    if _union_models(annotation):
        return "one of the variants below"
    if origin in (list, tuple, set, frozenset) and args:
        kind = {list: "list", tuple: "list", set: "set", frozenset: "set"}[origin]
        return f"{kind} of {type_text(args[0])}"
    if origin is dict and len(args) == 2:
        return f"mapping of {type_text(args[0])} to {type_text(args[1])}"
    if origin in (typing.Union, types.UnionType):
        return " or ".join(type_text(a) for a in args)
    if _is_model(annotation):
        return "mapping (keys below)"
    return getattr(annotation, "__name__", str(annotation))


def value_text(value) -> str:
    if value is None:
        return "none"
    if isinstance(value, bool):
        return "true" if value else "false"
    if isinstance(value, enum.Enum):
        return str(value.value)
    if isinstance(value, float) and math.isinf(value):
        return "inf" if value > 0 else "-inf"
    if isinstance(value, (set, frozenset)):
        return "[" + ", ".join(sorted(value_text(v) for v in value)) + "]"
    if isinstance(value, (list, tuple)):
        return "[" + ", ".join(value_text(v) for v in value) + "]"
    if isinstance(value, dict):
        return "{" + ", ".join(f"{k}: {value_text(v)}" for k, v in value.items()) + "}"
    if isinstance(value, str):
        return value if value else '""'
    return str(value)


def _default(info) -> object:
    if info.default is not PydanticUndefined:
        return info.default
    if info.default_factory is not None:
        return info.default_factory()
    return PydanticUndefined


def model_sections(model: type[BaseModel], title: str, description: str = "") -> list[Section]:
    """The model's keys as one section, followed by a section per variant of each tagged union in it."""
    main = Section(title, description or _doc(model))
    sections = [main]
    _collect(model, None, "", main, sections)
    return sections


def _doc(model: type[BaseModel]) -> str:
    doc = model.__doc__ or ""
    return "" if doc.startswith(f"{model.__name__}(") or doc == BaseModel.__doc__ else " ".join(doc.split())


def _collect(model: type[BaseModel], instance, prefix: str, section: Section, sections: list[Section]) -> None:
    for name, info in model.model_fields.items():
        key = f"{prefix}{name}"
        default = getattr(instance, name) if instance is not None else _default(info)
        inner, optional = _without_none(_unannotated(info.annotation))
        description = field_description(model, name)
        item = typing.get_args(inner)[0] if typing.get_origin(inner) is list else None
        variants = _union_models(item if item is not None else inner)
        if variants:
            _add_variants(key, info.annotation, default, description, variants, section, sections)
        elif _is_model(inner):
            if optional or default is PydanticUndefined:
                section.rows.append(Row(key, type_text(info.annotation), _default_text(default), description))
            nested = default if isinstance(default, BaseModel) else None
            _collect(inner, nested, f"{key}.", section, sections)
        elif item is not None and _is_model(_unannotated(item)):
            section.rows.append(Row(key, "list of mappings (keys below)", _default_text(default), description))
            _collect(_unannotated(item), None, f"{key}[].", section, sections)
        elif typing.get_origin(inner) is dict and _is_model(_unannotated(typing.get_args(inner)[1])):
            section.rows.append(Row(key, "mapping of names to mappings (keys below)", _default_text(default),
                                    description))
            _collect(_unannotated(typing.get_args(inner)[1]), None, f"{key}.<name>.", section, sections)
        else:
            section.rows.append(Row(key, type_text(info.annotation), _default_text(default), description))


def _default_text(default) -> str:
    if default is PydanticUndefined:
        return REQUIRED
    if isinstance(default, BaseModel):
        return "(keys below)"
    return value_text(default)


def _add_variants(key: str, annotation, default, description: str, variants: list[type[BaseModel]],
                  section: Section, sections: list[Section]) -> None:
    tag = _tag(variants[0])[0]
    kinds = ", ".join(_tag(v)[1] for v in variants)
    section.rows.append(Row(key, type_text(annotation), _default_text(default),
                            f"{description} Its `{tag}` is one of: {kinds} (keys below).".strip()))
    item_key = f"{key}[]" if typing.get_origin(_without_none(_unannotated(annotation))[0]) is list else key
    for variant in variants:
        tag_name, tag_value = _tag(variant)
        variant_section = Section(f"{item_key} with {tag_name}: {tag_value}", _doc(variant))
        sections.append(variant_section)
        _collect(variant, None, f"{item_key}.", variant_section, sections)


def sections_markdown(sections: list[Section], level: int = 2) -> str:
    parts = []
    for index, section in enumerate(sections):
        hashes = "#" * (level if index == 0 else level + 1)
        parts += [f"{hashes} {section.title}", ""]
        if section.description:
            parts += [section.description, ""]
        if section.rows:
            rows = [[code(r.key), cell(r.type), cell(r.default) if r.default == REQUIRED else code(r.default),
                     cell(r.description)] for r in section.rows]
            parts += [table(["key", "type", "default", "what it is"], rows), ""]
    return "\n".join(parts)
