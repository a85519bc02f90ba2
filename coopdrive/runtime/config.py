"""Loading a service's config: a YAML or JSON file, then `--set key.path=value` overrides.

Every error names the file and the key that was wrong, in one line.
"""

from __future__ import annotations

import json
from pathlib import Path
from typing import Any

import yaml
from pydantic import BaseModel, ValidationError


class ConfigError(ValueError):
    pass


def format_validation_error(source: str, error: ValidationError) -> str:
    problems = []
    for item in error.errors():
        key = ".".join(str(part) for part in item["loc"]) or "(top level)"
        problems.append(f"{key}: {item['msg']}")
    return f"{source}: " + "; ".join(problems)


def read_mapping(path: str | Path) -> dict[str, Any]:
    path = Path(path)
    try:
        text = path.read_text()
    except OSError as error:
        raise ConfigError(f"{path}: cannot read config: {error.strerror}") from None
    try:
        data = json.loads(text) if path.suffix == ".json" else yaml.safe_load(text)
    except (json.JSONDecodeError, yaml.YAMLError) as error:
        raise ConfigError(f"{path}: not valid {'JSON' if path.suffix == '.json' else 'YAML'}: {error}") from None
    if data is None:
        return {}
    if not isinstance(data, dict):
        raise ConfigError(f"{path}: the top level must be a mapping of keys, got {type(data).__name__}")
    return data


def apply_override(data: dict[str, Any], assignment: str) -> None:
    """Applies "a.b.c=value"; the value is parsed as YAML so numbers and lists keep their types."""
    key, sep, raw = assignment.partition("=")
    if not sep or not key:
        raise ConfigError(f"--set {assignment!r}: expected key.path=value")
    node = data
    parts = key.split(".")
    for part in parts[:-1]:
        child = node.setdefault(part, {})
        if not isinstance(child, dict):
            raise ConfigError(f"--set {assignment!r}: {part} is not a mapping")
        node = child
    node[parts[-1]] = yaml.safe_load(raw)


def load_config(model: type[BaseModel], path: str | Path | None = None, overrides: list[str] = ()) -> BaseModel:
    data = read_mapping(path) if path else {}
    for assignment in overrides:
        apply_override(data, assignment)
    return validate_config(model, data, str(path or "--set"))


def validate_config(model: type[BaseModel], data: dict[str, Any], source: str) -> BaseModel:
    """A mapping already in memory (e.g. one entry of a group spec), with the same one-line errors."""
    try:
        return model.model_validate(data)
    except ValidationError as error:
        raise ConfigError(format_validation_error(source, error)) from None
