"""The comments of the .proto files: the generated *_pb2 modules carry no source comments, so the message reference
reads each field's and enum value's comment (the `//` lines right above it and the one at the end of its line)
from proto/ beside the package."""

from __future__ import annotations

import re
from functools import lru_cache
from pathlib import Path

PROTO_ROOT = Path(__file__).resolve().parents[2] / "proto"

_BLOCK = re.compile(r"^\s*(message|enum|oneof)\s+(\w+)\s*\{")
_PACKAGE = re.compile(r"^\s*package\s+([\w.]+)\s*;")
# A field (`repeated Type name = 3;`, `map<K, V> name = 4;`) or an enum value (`NAME = 2;`).
_MEMBER = re.compile(r"^\s*(?:(?:repeated|optional)\s+)?(?:map<[^>]+>\s+|[\w.]+\s+)?(\w+)\s*=\s*-?\d+")


@lru_cache(maxsize=None)
def proto_comments(file_name: str) -> dict[tuple[str, str], str]:
    """(full name of the message or enum, member name) -> comment, for one file under proto/ (its descriptor's
    `file.name`, e.g. coopdrive/v1/control.proto); empty when the file is not there (an installed package)."""
    path = PROTO_ROOT / file_name
    if not path.is_file():
        return {}
    return _parse(path.read_text(encoding="utf-8").splitlines())


def _parse(lines: list[str]) -> dict[tuple[str, str], str]:
    comments: dict[tuple[str, str], str] = {}
    package, scopes, pending = "", [], []  # scopes: (kind, name) from the outermost
    for line in lines:
        code, _, trailing = line.partition("//")
        if not code.strip():
            pending = pending + [trailing.strip()] if trailing else []
            continue
        if match := _PACKAGE.match(code):
            package = match.group(1)
        elif match := _BLOCK.match(code):
            scopes.append((match.group(1), match.group(2)))
        elif code.strip().startswith("}"):
            scopes = scopes[:-1]
        elif (match := _MEMBER.match(code)) and scopes:
            owner = ".".join([package, *(name for kind, name in scopes if kind != "oneof")])
            text = " ".join(pending + ([trailing.strip()] if trailing else [])).strip()
            if text:
                comments[(owner, match.group(1))] = text
        pending = []
    return comments


def comment_of(descriptor, member_name: str) -> str:
    """The comment of a field or enum value of a message or enum descriptor."""
    return proto_comments(descriptor.file.name).get((descriptor.full_name, member_name), "")
