"""How a session reaches the others, as a service's diagnostics and the gateway's /health tell it.

- "mtls": a client of the router over TLS with its own certificate (what `coopdrive pki bus` writes): authenticated.
- "plain-loopback": plain TCP, every endpoint on this computer's loopback (the desk, a simulation).
- "plain": plain TCP reachable from elsewhere: anyone who reaches the port may publish.
"""

from __future__ import annotations

import json

import zenoh

MTLS = "mtls"
PLAIN_LOOPBACK = "plain-loopback"
PLAIN = "plain"
LOOPBACK_HOSTS = ("127.", "localhost", "[::1]")


def bus_mode(config: zenoh.Config) -> str:
    """The mode of a session opened on `config` (the endpoints it connects to and listens on, its TLS settings)."""
    endpoints = _endpoints(config, "connect")
    if json.loads(config.get_json("mode")) != "client":  # a client listens nowhere, whatever its defaults say
        endpoints += _endpoints(config, "listen")
    tls = json.loads(config.get_json("transport/link/tls")) or {}
    if endpoints and all(endpoint.startswith("tls/") for endpoint in endpoints) and tls.get("enable_mtls") \
            and tls.get("connect_certificate"):
        return MTLS
    if all(_host(endpoint).startswith(LOOPBACK_HOSTS) for endpoint in endpoints):
        return PLAIN_LOOPBACK
    return PLAIN


def _endpoints(config: zenoh.Config, side: str) -> list[str]:
    listed = json.loads(config.get_json(f"{side}/endpoints")) or []
    if isinstance(listed, dict):  # endpoints given per mode: {"router": [...], "peer": [...]}
        listed = [endpoint for endpoints in listed.values() for endpoint in endpoints]
    return [str(endpoint) for endpoint in listed]


def _host(endpoint: str) -> str:
    """"tcp/127.0.0.1:7447#iface=lo" -> "127.0.0.1:7447"."""
    return endpoint.split("/", 1)[-1].split("#", 1)[0]
