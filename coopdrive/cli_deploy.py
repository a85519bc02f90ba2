"""The deployment commands of `coopdrive`: health (container healthchecks), router (a Zenoh router without the
zenohd image), foxglove (the live bus to Foxglove) and pki (the vehicle's bus credentials; V2X's test PKI). One add_*
function per command."""

from __future__ import annotations

import json
import os
import re
import signal
import sys
import threading
import time
from pathlib import Path

from coopdrive.exit_status import EXIT_FAILED, EXIT_OK, EXIT_USAGE
from coopdrive.services.v2x.cli import add_pki_commands as add_v2x_pki_commands

DEFAULT_FOXGLOVE_PORT = 8765
HEALTH_RETRY_S = 0.1
# Zenoh's log filter (Rust's tracing syntax): set, the router logs what it selects (Zenoh writes it on stdout).
ZENOH_LOG_VARIABLE = "RUST_LOG"


def add_commands(commands) -> None:
    add_health_command(commands)
    add_router_command(commands)
    add_foxglove_command(commands)
    add_pki_command(commands)


def wait_for_stop_signal() -> None:
    """Blocks until SIGINT or SIGTERM (the main thread's handlers are replaced for good: the caller ends)."""
    from coopdrive.runtime.signal_wait import wait_hearing_signals

    stop = threading.Event()
    for signum in (signal.SIGINT, signal.SIGTERM):
        signal.signal(signum, lambda *_: stop.set())
    wait_hearing_signals(stop)


def add_health_command(commands) -> None:
    health = commands.add_parser("health", help="exit 0 when a service is alive on the bus (container healthcheck)")
    health.add_argument("--connect", action="append", default=[])
    health.add_argument("--zenoh-config", type=Path, help="Zenoh JSON5 config (the vehicle's bus credentials)")
    health.add_argument("--vehicle", default="ego")
    health.add_argument("--service", action="append", required=True,
                        help="repeat for several (a group's): all must be alive")
    health.add_argument("--timeout", type=float, default=2.0)
    health.set_defaults(handler=_health)


def _health(args) -> int:
    from coopdrive.bus import Bus, BusConfig

    bus = Bus(BusConfig(connect=args.connect, listen=[],
                        zenoh_config_file=str(args.zenoh_config) if args.zenoh_config else None))
    wanted = {service: bus.layout.liveliness(args.vehicle, service) for service in args.service}
    # A session just opened may be answered before it has learned the bus's tokens (an empty or partial reply
    # at once): ask again until every one is there or the time is up.
    deadline = time.monotonic() + args.timeout
    tokens: set[str] = set()
    try:
        while True:
            tokens |= set(bus.alive_tokens(bus.layout.liveliness(args.vehicle, "*"),
                                           timeout_s=max(0.1, deadline - time.monotonic())))
            if set(wanted.values()) <= tokens or time.monotonic() >= deadline:
                break
            time.sleep(HEALTH_RETRY_S)
    finally:
        bus.close()
    alive = {service: key in tokens for service, key in wanted.items()}
    for service, up in alive.items():
        print(f"{args.vehicle}/{service}: {'alive' if up else 'not alive'}")
    return EXIT_OK if all(alive.values()) else EXIT_FAILED


def add_router_command(commands) -> None:
    router = commands.add_parser("router", help="a Zenoh router (what the zenohd container runs) until Ctrl-C; "
                                                f"{ZENOH_LOG_VARIABLE}=... selects Zenoh's log (on stdout)")
    router.add_argument("--listen", action="append", default=[], metavar="ENDPOINT",
                        help="e.g. tcp/0.0.0.0:7447 (default: the config's, else tcp/0.0.0.0:7447)")
    router.add_argument("--config", type=Path, help="zenohd's JSON5 config, e.g. deploy/config/zenohd.json5")
    router.add_argument("--count-denials", action="store_true",
                        help="count the messages the access control refuses and print the count when it changes "
                             "(traces every access decision: some CPU)")
    router.set_defaults(handler=_router)


def _router(args) -> int:
    import zenoh

    from coopdrive.bus.router_denials import RouterDenials

    denials = RouterDenials(os.environ.get(ZENOH_LOG_VARIABLE)) if args.count_denials else None
    if denials is not None:
        denials.start()
        os.environ[ZENOH_LOG_VARIABLE] = denials.log_filter
    if os.environ.get(ZENOH_LOG_VARIABLE):
        # Zenoh's own log (e.g. the access control's decisions at trace level), on stdout, only when asked for.
        zenoh.init_log_from_env_or("error")
    try:
        return _serve_router(args)
    finally:
        if denials is not None:
            denials.close()


def _serve_router(args) -> int:
    import zenoh

    from coopdrive.runtime.config import ConfigError

    from coopdrive.bus.credentials_error import REMEDY

    if args.config and not args.config.is_file():
        raise ConfigError(f"router --config {args.config}: no such file (the vehicle's router: {REMEDY})")
    try:
        config = zenoh.Config.from_file(str(args.config)) if args.config else zenoh.Config()
        config.insert_json5("mode", '"router"')
        config.insert_json5("scouting/multicast/enabled", "false")
        if args.listen or not args.config:
            config.insert_json5("listen/endpoints", json.dumps(args.listen or ["tcp/0.0.0.0:7447"]))
        session = zenoh.open(config)
    except zenoh.ZError as error:
        # Zenoh's messages end with where in its Rust source they were raised: not the user's business.
        reason = re.sub(r" at \S+\.rs:\d+\.?$", "", " ".join(str(error).split()))
        given = [f"--config {args.config}"] if args.config else []
        given += [f"--listen {endpoint}" for endpoint in args.listen]
        raise ConfigError(f"router {' '.join(given)}: {reason}") from None
    print(f"zenoh router {session.zid()} listening", flush=True)
    try:
        wait_for_stop_signal()
    finally:
        session.close()
    return EXIT_OK


def add_foxglove_command(commands) -> None:
    fox = commands.add_parser("foxglove", help="serve the live bus to Foxglove (WebSocket) until Ctrl-C")
    fox.add_argument("--connect", action="append", default=[], metavar="ENDPOINT",
                     help="the bus to serve, e.g. tcp/127.0.0.1:7447 (a router, or a run's --listen)")
    fox.add_argument("--port", type=int, default=DEFAULT_FOXGLOVE_PORT, help="WebSocket port (0: any free one)")
    fox.add_argument("--host", default="0.0.0.0", help="address to serve on")
    fox.add_argument("--map", metavar="NAME", help="lane map to draw (default: the one geolocation reports)")
    fox.add_argument("--vehicle", default="ego", help="vehicle id of the bridge's liveliness token")
    fox.add_argument("--zenoh-config", type=Path, help="Zenoh JSON5 config (an observer's bus credentials): then "
                                                       "the bridge serves --vehicle's topics only")
    fox.set_defaults(handler=_foxglove)


def _foxglove(args) -> int:
    from coopdrive.bus import Bus, BusConfig
    from coopdrive.roadmap import RoadMap
    from coopdrive.runtime.config import ConfigError
    from coopdrive.recording.foxglove_live import FoxgloveBridge

    try:
        road_map = RoadMap.load(args.map) if args.map else None
    except (OSError, ValueError) as error:
        raise ConfigError(f"foxglove --map {args.map}: {error}") from None
    bus = Bus(BusConfig(connect=args.connect, zenoh_config_file=str(args.zenoh_config) if args.zenoh_config else None))
    try:
        bridge = FoxgloveBridge(bus, args.port, args.host, road_map, args.vehicle if args.zenoh_config else "*")
    except RuntimeError as error:
        bus.close()
        print(f"coopdrive: foxglove: cannot serve on {args.host}:{args.port}: {error}", file=sys.stderr)
        return EXIT_FAILED
    # Healthchecks and the gateway see the bridge like a service.
    bus.declare_token(bus.layout.liveliness(args.vehicle, "foxglove"))
    print(f"Foxglove: open ws://{args.host}:{bridge.port} (Foxglove WebSocket connection)", flush=True)
    try:
        wait_for_stop_signal()
    finally:
        bridge.close()
        bus.close()
    return EXIT_OK


def add_pki_command(commands) -> None:
    from coopdrive.bus.bus_credentials import DEFAULT_DAYS, DEFAULT_ROUTER_ENDPOINT, DEFAULT_ROUTER_LISTEN

    pki = commands.add_parser("pki", help="credentials: the vehicle's bus (mutual TLS), V2X's test PKI")
    pki_commands = pki.add_subparsers(dest="pki_command", required=True)
    bus = pki_commands.add_parser("bus", help="a CA, a certificate, key and Zenoh config per service, the gateway and "
                                              "each observer, and the router's config with the access rules")
    bus.add_argument("directory", type=Path, help="a new or empty folder")
    bus.add_argument("--vehicle", required=True, help="the vehicle id the services run as (their keys' prefix)")
    bus.add_argument("--observer", action="append", default=[], metavar="NAME",
                     help="a certificate that may only subscribe (a team laptop, a recorder); repeat for several")
    bus.add_argument("--days", type=float, default=DEFAULT_DAYS, help=f"validity (default {DEFAULT_DAYS} days)")
    bus.add_argument("--router", default=DEFAULT_ROUTER_ENDPOINT, metavar="ENDPOINT",
                     help=f"where the services reach the router (default {DEFAULT_ROUTER_ENDPOINT})")
    bus.add_argument("--router-listen", default=DEFAULT_ROUTER_LISTEN, metavar="ENDPOINT",
                     help=f"where the router listens (default {DEFAULT_ROUTER_LISTEN})")
    bus.add_argument("--router-host", action="append", default=[], metavar="HOST",
                     help="another name or address the router is reached at (another computer's view); repeatable")
    bus.add_argument("--simulated", action="store_true",
                     help="a simulated vehicle (the desk): a certificate for the simulator too, and everyone hears the "
                          "world and the lockstep's markers")
    bus.add_argument("--mounted-at", type=Path, metavar="PATH",
                     help="where the containers see the folder: the configs name their files under it (default: "
                          "the folder itself)")
    bus.set_defaults(handler=_pki_bus)
    add_v2x_pki_commands(pki_commands)


def _pki_bus(args) -> int:
    from coopdrive.bus.bus_credentials import BusCredentialsRequest, write_bus_credentials

    request = BusCredentialsRequest(args.directory, args.vehicle, tuple(args.observer), args.days, args.router,
                                    args.router_listen, tuple(args.router_host), args.mounted_at, args.simulated)
    try:
        names = write_bus_credentials(request)
    except (OSError, ValueError) as error:
        print(f"coopdrive: pki bus: {error}", file=sys.stderr)
        return EXIT_USAGE
    print(f"bus credentials of vehicle {args.vehicle} in {args.directory}, valid {args.days:g} days: "
          f"{', '.join(names)}")
    print(f"router: coopdrive router --config {args.directory / 'router' / 'zenohd.json5'}")
    return EXIT_OK
