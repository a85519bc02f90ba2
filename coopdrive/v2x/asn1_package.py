"""The ASN.1 modules of one folder of coopdrive.v2x.asn1, parsed once (the parse cached on disk, as the security
modules' is) and compiled once per process, on first use.

    spec = PackageSpec("coopdrive.v2x.asn1.dsrc", "dsrc").get()      # an asn1tools Specification (UPER)
"""

from __future__ import annotations

import threading
from importlib import resources
from pathlib import Path

import asn1tools

from coopdrive.v2x.asn1_cache import parsed_cached
from coopdrive.v2x.its_pdu import default_cache_dir


class PackageSpec:
    def __init__(self, package: str, cache_name: str, codec: str = "uper"):
        self.package, self.cache_name, self.codec = package, cache_name, codec
        self._lock = threading.Lock()
        self._spec: asn1tools.compiler.Specification | None = None

    def paths(self) -> list[str]:
        folder = resources.files(self.package)
        return sorted(str(folder.joinpath(entry.name)) for entry in folder.iterdir() if entry.name.endswith(".asn"))

    def get(self) -> asn1tools.compiler.Specification:
        if self._spec is None:
            with self._lock:
                if self._spec is None:
                    parsed = parsed_cached(self.paths(), Path(default_cache_dir()), self.cache_name)
                    self._spec = asn1tools.compile_dict(parsed, self.codec)
        return self._spec
