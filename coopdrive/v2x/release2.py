"""CPM v2 (TS 103 324) and VAM (TS 103 300-3) of ETSI ITS Release 2: UPER decode to plain JSON-ready values.

    content = release2_content("cpm", uper)     # dict (bytes as hex, BIT STRINGs as hex, CHOICEs as {name: value})

The eight modules (asn1/release2, from Vanetza's patched ETSI set) are parsed once (about 5 s; the parse is
cached on disk like the security modules) and compiled per process. We decode these messages to show and
count them; the v2x service takes VAMs (vru.py).
"""

from __future__ import annotations

from coopdrive.v2x.asn1_package import PackageSpec

TOP_TYPE_OF_MESSAGE = {"cpm": "CollectivePerceptionMessage", "vam": "VAM"}
_SPEC = PackageSpec("coopdrive.v2x.asn1.release2", "release2")


def release2_spec():
    """The compiled modules (compiled once per process, on first use)."""
    return _SPEC.get()


def release2_content(message: str, uper: bytes) -> dict:
    """The decoded message as JSON-ready values; raises whatever asn1tools raises on bad input."""
    return plain(release2_spec().decode(TOP_TYPE_OF_MESSAGE[message], uper))


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
