"""asn1tools' parse of a set of ASN.1 modules, cached on disk: parsing takes about a second per set, reading the
cache some milliseconds.

The cache file is keyed by the modules' bytes, the asn1tools version and the marshal format, and holds the parsed
dict in Python's marshal format: plain data (dicts, lists, tuples, strings, numbers), read without the compiler. It
was a Python literal read with ast.literal_eval, which on CPython 3.11 raises "SystemError: AST constructor
recursion depth mismatch" when another thread compiles meanwhile (CPython issue 106905): the v2x service reads it
in a thread of its own while the main thread imports.
"""

from __future__ import annotations

import hashlib
import marshal
import os
import sys
from pathlib import Path

import asn1tools


def parsed_cached(paths: list[str], cache_dir: Path, name: str) -> dict:
    """asn1tools.parse_files(paths), cached on disk as `<name>-<hash>.marshal` in cache_dir; a damaged or foreign
    cache file is parsed again and replaced, a cache that cannot be written only costs the parse."""
    digest = hashlib.sha256(f"{asn1tools.__version__} marshal {marshal.version} {sys.version_info[:2]}".encode())
    for path in paths:
        digest.update(Path(path).read_bytes())
    key = digest.hexdigest()
    cached = cache_dir / f"{name}-{key[:24]}.marshal"
    if cached.is_file():
        try:
            stored = marshal.loads(cached.read_bytes())
        except (ValueError, EOFError, TypeError, OSError):
            stored = None
        # The file holds (its whole key, the parse): damaged bytes that happen to read as data are not trusted.
        if isinstance(stored, tuple) and len(stored) == 2 and stored[0] == key and isinstance(stored[1], dict):
            return stored[1]
    parsed = asn1tools.parse_files(paths)
    try:
        cache_dir.mkdir(parents=True, exist_ok=True)
        partial = cached.with_suffix(f".{os.getpid()}.tmp")
        partial.write_bytes(marshal.dumps((key, parsed)))
        partial.replace(cached)
    except (OSError, ValueError):
        pass  # a read-only home only costs start-up time; ValueError: a value marshal cannot write
    return parsed
