"""Two network namespaces joined by a veth pair: a wire between two stations on one machine, for the live V2X
tests. Each station runs in its own namespace (`ip netns exec NAME ...`) on its end of the pair, so every GN frame
crosses a real network interface, as it would an 802.11p OCB interface.

    with VethPair.create() as pair:        # skips the test, naming the `ip` error, where namespaces cannot be made
        pair.command(pair.a, "python", "-m", ...)   # argv that runs inside namespace a

The namespaces, and with them the veth pair, are removed when the block ends, whatever happened in it.
"""

from __future__ import annotations

import os
import secrets
import subprocess
from dataclasses import dataclass

import pytest

from tests.system_packages import require

# How long one `ip` command may take on a loaded machine.
IP_TIMEOUT_S = 30.0
# Linux interface names hold at most 15 characters (IFNAMSIZ - 1): "cdv" + 8 hex digits + one letter fits.
TOKEN_BYTES = 4


@dataclass(frozen=True)
class Station:
    """One end of the wire: its namespace and the interface in it."""

    namespace: str
    interface: str


class NamespaceError(RuntimeError):
    """An `ip` command failed: its message is the command and ip's own error line."""


def _ip(*args: str) -> None:
    result = subprocess.run([require("ip"), *args], capture_output=True, text=True, timeout=IP_TIMEOUT_S)
    if result.returncode != 0:
        error = (result.stderr.strip().splitlines() or [f"exit status {result.returncode}"])[-1]
        raise NamespaceError(f"`ip {' '.join(args)}`: {error}")


class VethPair:
    """Namespaces cd<token>a and cd<token>b, with veth ends cdv<token>a and cdv<token>b in them, links up."""

    def __init__(self, token: str, together: bool):
        self.a = Station(f"cd{token}a", f"cdv{token}a")
        # together: both ends in namespace a (a desk with two cards), namespace b made but left empty.
        self.b = Station(self.a.namespace if together else f"cd{token}b", f"cdv{token}b")
        self._namespaces = (self.a.namespace, f"cd{token}b")

    @classmethod
    def create(cls, together: bool = False) -> "VethPair":
        """A new pair, unique to this process; skips the calling test where namespaces cannot be made (no root,
        no CAP_SYS_ADMIN, a container without them), with ip's error line as the reason."""
        pair = cls(f"{os.getpid() % 0xFFFF:04x}{secrets.token_hex(TOKEN_BYTES // 2)}", together)
        try:
            _ip("netns", "add", pair.a.namespace)
        except NamespaceError as error:
            pytest.skip(f"network namespaces cannot be made here: {error}")
        try:
            pair._build()
        except BaseException:
            pair.remove()
            raise
        return pair

    def _build(self) -> None:
        _ip("netns", "add", self._namespaces[1])
        _ip("link", "add", self.a.interface, "netns", self.a.namespace, "type", "veth",
            "peer", "name", self.b.interface, "netns", self.b.namespace)
        for station in (self.a, self.b):
            # No IPv6 link-local address, so no neighbour discovery or MLD frames: only the stations' GN frames
            # cross the wire.
            _ip("-n", station.namespace, "link", "set", station.interface, "addrgenmode", "none")
            _ip("-n", station.namespace, "link", "set", station.interface, "up")
        for namespace in self._namespaces:
            # Loopback, for the Zenoh bus a station's harness opens on 127.0.0.1 inside its namespace.
            _ip("-n", namespace, "link", "set", "lo", "up")

    def command(self, station: Station, *argv: str) -> list[str]:
        """The argv that runs `argv` inside the station's namespace."""
        return [require("ip"), "netns", "exec", station.namespace, *argv]

    def remove(self) -> None:
        """Deletes both namespaces (the veth pair goes with them); a namespace already gone is no error."""
        for namespace in self._namespaces:
            subprocess.run([require("ip"), "netns", "delete", namespace], capture_output=True, timeout=IP_TIMEOUT_S)

    def __enter__(self) -> "VethPair":
        return self

    def __exit__(self, *_exc) -> None:
        self.remove()
