"""The deployment commands of `coopdrive`: health (container healthchecks), router (a Zenoh router without the
zenohd image) and foxglove (the live bus to Foxglove). One add_* function per command."""

from __future__ import annotations

import json
import re
import signal
import sys
import threading
import time
from pathlib import Path

from coopdrive.exit_status import EXIT_FAILED, EXIT_OK

DEFAULT_FOXGLOVE_PORT = 8765
HEALTH_RETRY_S = 0.1


def add_commands(commands) -> None:
    add_health_command(commands)
    add_router_command(commands)
    add_foxglove_command(commands)


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
    health.add_argument("--vehicle", default="ego")
    health.add_argument("--service", action="append", required=True,
                        help="repeat for several (a group's): all must be alive")
    health.add_argument("--timeout", type=float, default=2.0)
    health.set_defaults(handler=_health)


def _health(args) -> int:
    from coopdrive.bus import Bus, BusConfig

    bus = Bus(BusConfig(connect=args.connect, listen=[]))
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
    router = commands.add_parser("router", help="a Zenoh router (what the zenohd container runs) until Ctrl-C")
    router.add_argument("--listen", action="append", default=[], metavar="ENDPOINT",
                        help="e.g. tcp/0.0.0.0:7447 (default: the config's, else tcp/0.0.0.0:7447)")
    router.add_argument("--config", type=Path, help="zenohd's JSON5 config, e.g. deploy/config/zenohd.json5")
    router.set_defaults(handler=_router)


def _router(args) -> int:
    import zenoh

    from coopdrive.runtime.config import ConfigError

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
    bus = Bus(BusConfig(connect=args.connect))
    try:
        bridge = FoxgloveBridge(bus, args.port, args.host, road_map)
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
