"""`coopdrive pki bus DIR --vehicle ID`: the vehicle's bus credentials in one folder.

    DIR/ca/ca.pem, ca-key.pem             the vehicle's bus CA (its key issues more; keep it off the car)
    DIR/router/                           the router's certificate and key, the CA, zenohd.json5 (mTLS + access control)
    DIR/<service>/, DIR/gateway/          each one's certificate and key (common name: the service), the CA and
                                          zenoh.json5: a client of the router over mutual TLS
    DIR/<observer>/                       the same for each observer asked for

Each folder is what one container mounts (read-only): the configs name their files under `mounted_at` (default: DIR
itself), so the same folder works where the containers see it elsewhere.
"""

from __future__ import annotations

import datetime
import json
from dataclasses import dataclass
from pathlib import Path
from typing import TYPE_CHECKING

from coopdrive.bus.bus_grant import AUTHORITY_NAME, ROUTER_NAME, bus_grants, checked_name
from coopdrive.bus.router_access import access_control
from coopdrive.bus.simulated_grant import heard_on_a_simulated_bus, simulated_grants

if TYPE_CHECKING:  # the X.509 work is loaded only when credentials are made, not by every command's parser
    from coopdrive.bus.bus_authority import BusAuthority

DEFAULT_DAYS = 365
# Where the router listens and where the services reach it: on the vehicle all share the host's network.
DEFAULT_ROUTER_LISTEN = "tls/0.0.0.0:7447"
DEFAULT_ROUTER_ENDPOINT = "tls/127.0.0.1:7447"
# Names the router's certificate answers to besides its endpoint's host (verify_name_on_connect).
LOCAL_HOSTS = ("localhost", "127.0.0.1")
CERTIFICATE = "cert.pem"
KEY = "key.pem"
AUTHORITY_CERTIFICATE = "ca.pem"
CLIENT_CONFIG = "zenoh.json5"
ROUTER_CONFIG = "zenohd.json5"
HEADER = ("// Written by `coopdrive pki bus`: make it again rather than edit it (the access rules come from the services'\n"
          "// topic declarations).\n")


@dataclass(frozen=True)
class BusCredentialsRequest:
    directory: Path
    vehicle_id: str
    observers: tuple[str, ...] = ()
    days: float = DEFAULT_DAYS
    router_endpoint: str = DEFAULT_ROUTER_ENDPOINT
    router_listen: str = DEFAULT_ROUTER_LISTEN
    router_hosts: tuple[str, ...] = ()
    mounted_at: Path | None = None
    # A simulated vehicle (the desk): the simulator gets a certificate, and everyone hears the world and the lockstep.
    simulated: bool = False


def write_bus_credentials(request: BusCredentialsRequest, now: datetime.datetime | None = None) -> list[str]:
    """Writes the folder; returns the common names it made certificates for (the router's first). ValueError naming
    the problem when the request cannot be met, before anything is written."""
    from coopdrive.bus.bus_authority import BusAuthority

    directory = request.directory
    vehicle_id = checked_name("vehicle id", request.vehicle_id)
    grants = (simulated_grants(vehicle_id, request.observers) if request.simulated
              else bus_grants(vehicle_id, request.observers))
    heard = heard_on_a_simulated_bus() if request.simulated else ()
    router_host = _tls_host("router endpoint", request.router_endpoint)
    _tls_host("router listen endpoint", request.router_listen)
    if directory.exists() and any(directory.iterdir()):
        raise ValueError(f"{directory} is not empty: not overwriting credentials (remove it to make new ones)")
    mounted_at = request.mounted_at or directory.resolve()
    authority = BusAuthority.create(f"coopdrive bus CA of {request.vehicle_id}", request.days, now)
    _folder(directory / AUTHORITY_NAME)
    authority.write(directory / AUTHORITY_NAME / AUTHORITY_CERTIFICATE, directory / AUTHORITY_NAME / "ca-key.pem")

    hosts = tuple(dict.fromkeys((router_host, *request.router_hosts, *LOCAL_HOSTS)))
    _issue(authority, directory, ROUTER_NAME, request.days, hosts, now)
    router = router_config(mounted_at / ROUTER_NAME, request.router_listen,
                           access_control(grants, request.vehicle_id, heard=heard))
    (directory / ROUTER_NAME / ROUTER_CONFIG).write_text(HEADER + json.dumps(router, indent=2) + "\n")
    for grant in grants:
        _issue(authority, directory, grant.subject, request.days, (), now)
        client = client_config(mounted_at / grant.subject, request.router_endpoint)
        (directory / grant.subject / CLIENT_CONFIG).write_text(HEADER + json.dumps(client, indent=2) + "\n")
    return [ROUTER_NAME, *(grant.subject for grant in grants)]


def tls_files(folder: Path) -> dict:
    return {"root_ca_certificate": str(folder / AUTHORITY_CERTIFICATE), "enable_mtls": True,
            # A link whose other end's certificate expires is closed then, not at its next connection.
            "close_link_on_expiration": True}


def client_config(folder: Path, router_endpoint: str) -> dict:
    """A client of the router only (no listening, no scouting): nothing reaches it except through the router's
    access control."""
    tls = {**tls_files(folder), "connect_certificate": str(folder / CERTIFICATE),
           "connect_private_key": str(folder / KEY)}
    return {"mode": "client", "connect": {"endpoints": [router_endpoint]},
            "scouting": {"multicast": {"enabled": False}, "gossip": {"enabled": False}},
            "transport": {"link": {"tls": tls}}}


def router_config(folder: Path, listen: str, rules: dict) -> dict:
    tls = {**tls_files(folder), "listen_certificate": str(folder / CERTIFICATE),
           "listen_private_key": str(folder / KEY)}
    return {"mode": "router", "listen": {"endpoints": [listen]},
            "scouting": {"multicast": {"enabled": False}},
            # TLS only: a plain TCP or UDP link would carry no certificate to match the rules with.
            "transport": {"link": {"protocols": ["tls"], "tls": tls}},
            "access_control": rules}


def _issue(authority: BusAuthority, directory: Path, name: str, days: float, hosts: tuple[str, ...],
           now: datetime.datetime | None) -> None:
    from coopdrive.bus.bus_authority import write_pair

    folder = _folder(directory / name)
    certificate, key = authority.issue(name, days, hosts, now)
    write_pair(certificate, key, folder / CERTIFICATE, folder / KEY)
    (folder / AUTHORITY_CERTIFICATE).write_bytes((directory / AUTHORITY_NAME / AUTHORITY_CERTIFICATE).read_bytes())


def _folder(path: Path) -> Path:
    path.mkdir(parents=True, exist_ok=True)
    return path


def _tls_host(what: str, endpoint: str) -> str:
    """The host of a `tls/HOST:PORT` endpoint; ValueError naming `what` for any other."""
    protocol, _, address = endpoint.partition("/")
    host, _, port = address.rpartition(":")
    if protocol != "tls" or not host or not port.isdigit():
        raise ValueError(f"{what} {endpoint!r} must be tls/HOST:PORT (the bus is TLS only)")
    return host.strip("[]")
