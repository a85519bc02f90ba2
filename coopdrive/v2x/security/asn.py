"""OER codec of the security envelope (EtsiTs103097Data, certificates), compiled once per process.

Parsing the three modules takes about a second, so the parsed dict is cached on disk next to the ITS
schemas (same directory and scheme as its_pdu.py: a Python literal keyed by the files' hash and the
asn1tools version, read back with ast.literal_eval) and the compiled specification is kept per process.
"""

from __future__ import annotations

import ast
import hashlib
import os
import threading
from importlib import resources
from pathlib import Path

import asn1tools

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


def parsed_cached(paths: list[str], cache_dir: Path, name: str) -> dict:
    """asn1tools.parse_files(paths), cached on disk as `<name>-<hash>.py-literal` in cache_dir."""
    digest = hashlib.sha256(asn1tools.__version__.encode())
    for path in paths:
        digest.update(Path(path).read_bytes())
    cached = cache_dir / f"{name}-{digest.hexdigest()[:24]}.py-literal"
    if cached.is_file():
        try:
            return ast.literal_eval(cached.read_text(encoding="utf-8"))
        except (ValueError, SyntaxError, MemoryError, RecursionError):
            pass  # a damaged cache file is rebuilt below
    parsed = asn1tools.parse_files(paths)
    try:
        cache_dir.mkdir(parents=True, exist_ok=True)
        partial = cached.with_suffix(f".{os.getpid()}.tmp")
        partial.write_text(repr(parsed), encoding="utf-8")
        partial.replace(cached)
    except OSError:
        pass  # a read-only home only costs start-up time
    return parsed


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
