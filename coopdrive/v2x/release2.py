"""CPM v2 (TS 103 324) and VAM (TS 103 300-3) of ETSI ITS Release 2: UPER decode to plain JSON-ready values.

    content = release2_content("cpm", uper)     # dict (bytes as hex, BIT STRINGs as hex, CHOICEs as {name: value})

The eight modules (asn1/release2, from Vanetza's patched ETSI set) are parsed once (about 5 s; the parse is
cached on disk like the security modules) and compiled per process. We decode these messages to show and
count them; nothing in the stack consumes them yet.
"""

from __future__ import annotations

import threading
from importlib import resources
from pathlib import Path

import asn1tools

from coopdrive.v2x.its_pdu import default_cache_dir
from coopdrive.v2x.security.asn import parsed_cached

TOP_TYPE_OF_MESSAGE = {"cpm": "CollectivePerceptionMessage", "vam": "VAM"}
_lock = threading.Lock()
_spec: asn1tools.compiler.Specification | None = None


def _spec_once() -> asn1tools.compiler.Specification:
    global _spec
    if _spec is None:
        with _lock:
            if _spec is None:
                package = resources.files("coopdrive.v2x.asn1.release2")
                paths = sorted(str(package.joinpath(entry.name)) for entry in package.iterdir()
                               if entry.name.endswith(".asn"))
                _spec = asn1tools.compile_dict(parsed_cached(paths, Path(default_cache_dir()), "release2"), "uper")
    return _spec


def release2_content(message: str, uper: bytes) -> dict:
    """The decoded message as JSON-ready values; raises whatever asn1tools raises on bad input."""
    return plain(_spec_once().decode(TOP_TYPE_OF_MESSAGE[message], uper))


def plain(value):
    """asn1tools values as JSON: bytes -> hex, (bytes, bits) BIT STRING -> hex, (name, value) CHOICE -> {name: v}."""
    if isinstance(value, dict):
        return {key: plain(item) for key, item in value.items()}
    if isinstance(value, list):
        return [plain(item) for item in value]
    if isinstance(value, (bytes, bytearray)):
        return bytes(value).hex()
    if isinstance(value, tuple) and len(value) == 2:
        if isinstance(value[0], (bytes, bytearray)) and isinstance(value[1], int):
            return bytes(value[0]).hex()
        if isinstance(value[0], str):
            return {value[0]: plain(value[1])}
    return value
