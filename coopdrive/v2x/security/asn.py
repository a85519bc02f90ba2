"""OER codec of the security envelope (EtsiTs103097Data, certificates), compiled once per process.

Parsing the three modules takes about a second, so the parsed dict is cached on disk next to the ITS
schemas (coopdrive/v2x/asn1_cache.py) and the compiled specification is kept per process.
"""

from __future__ import annotations

import threading
from importlib import resources
from pathlib import Path

import asn1tools

from coopdrive.v2x.asn1_cache import parsed_cached
from coopdrive.v2x.its_pdu import default_cache_dir

SECURITY_FILES = ("IEEE1609dot2BaseTypes.asn", "IEEE1609dot2.asn", "TS103097v131.asn")
DATA_TYPE = "EtsiTs103097Data"
CERTIFICATE_TYPE = "EtsiTs103097Certificate"
TBS_DATA_TYPE = "ToBeSignedData"
TBS_CERTIFICATE_TYPE = "ToBeSignedCertificate"

_lock = threading.Lock()
_spec: asn1tools.compiler.Specification | None = None


def _paths() -> list[str]:
    package = resources.files("coopdrive.v2x.asn1.security")
    return [str(package.joinpath(name)) for name in SECURITY_FILES]


def security_spec(cache_dir: Path | None = None) -> asn1tools.compiler.Specification:
    """The compiled OER specification of the security modules (shared, thread-safe to build)."""
    global _spec
    if _spec is None:
        with _lock:
            if _spec is None:
                parsed = parsed_cached(_paths(), Path(cache_dir) if cache_dir else default_cache_dir(), "security")
                _spec = asn1tools.compile_dict(parsed, "oer")
    return _spec


def encode(type_name: str, value: dict, check_types: bool = True) -> bytes:
    """check_types=False only for values that came out of decode (a third of the cost is the type check)."""
    return security_spec().encode(type_name, value, check_types=check_types)


def decode(type_name: str, data: bytes) -> dict:
    """Decode; raises whatever asn1tools raises on garbage (callers map it to a reject reason)."""
    return security_spec().decode(type_name, data)
