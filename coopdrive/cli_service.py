"""`coopdrive service` and `coopdrive group`: what every process of a run (and each container) runs, and the
command line's error handling. The launcher's forked processes call main() here: it loads neither the launcher nor
the judging the rest of the command line reaches (coopdrive/cli.py)."""

from __future__ import annotations

import argparse
import json
import logging
import sys
from pathlib import Path

from coopdrive.bus.credentials_error import BusCredentialsError
from coopdrive.exit_status import EXIT_FAILED, EXIT_OK, EXIT_USAGE
from coopdrive.launch.run_aborted import RunAborted
from coopdrive.runtime.config import ConfigError
from coopdrive.runtime.priority import nice_session_as_asked
from coopdrive.runtime.service import HardwareUnavailable


def main(argv: list[str] | None = None) -> int:
    """`coopdrive service ...` or `coopdrive group ...` alone."""
    parser = argparse.ArgumentParser(prog="coopdrive", description="One process of the stack")
    add_commands(parser.add_subparsers(dest="command", required=True))
    return run_command(parser, argv)


def run_command(parser: argparse.ArgumentParser, argv: list[str] | None) -> int:
    """Parses and runs a command; what goes wrong in a way a user can mend is one line on stderr, not a trace."""
    args = parser.parse_args(argv)
    logging.basicConfig(level=logging.WARNING if not getattr(args, "verbose", False) else logging.INFO,
                        format="%(asctime)s %(name)s %(levelname)s %(message)s")
    try:
        nice_session_as_asked()
        return args.handler(args)
    except (ConfigError, BusCredentialsError) as error:
        print(f"coopdrive: {error}", file=sys.stderr)
        return EXIT_USAGE
    except (HardwareUnavailable, RunAborted) as error:
        print(f"coopdrive: {error}", file=sys.stderr)
        return EXIT_FAILED
    except KeyboardInterrupt:
        return EXIT_FAILED


def add_commands(commands) -> None:
    service = commands.add_parser("service", help="run one service (what docker compose runs)")
    service.add_argument("name")
    service.add_argument("--config", type=Path, help="YAML or JSON config of the service")
    service.add_argument("--vehicle", default="ego", help="vehicle id, the second level of every key")
    service.add_argument("--connect", action="append", default=[], help="Zenoh endpoint to connect to")
    service.add_argument("--listen", action="append", default=[], help="Zenoh endpoint to listen on")
    service.add_argument("--zenoh-config", type=Path, help="Zenoh JSON5 config (TLS, access control)")
    service.add_argument("--clock", choices=["wall", "sim"], default="wall")
    service.add_argument("--clock-step", type=float, metavar="SECONDS",
                         help="with --clock sim: the simulator's step, so only the clocks this service runs on come")
    service.add_argument("--set", action="append", default=[], metavar="KEY=VALUE", help="override a config key")
    service.add_argument("--hardware-retry", type=float, metavar="SECONDS",
                         help="a device that cannot be opened: say so once and try again this often (default: exit)")
    service.add_argument("-v", "--verbose", action="store_true")
    service.set_defaults(handler=_service)

    group = commands.add_parser("group", help="run several services in one process (a whole stack in simulation)")
    group.add_argument("spec", type=Path, help='JSON: [{"service": NAME, "vehicle": ID, "config": {...}}, ...]')
    group.add_argument("--connect", action="append", default=[], help="Zenoh endpoint to connect to")
    group.add_argument("--listen", action="append", default=[], help="Zenoh endpoint to listen on")
    group.add_argument("--clock", choices=["wall", "sim"], default="wall")
    group.add_argument("--clock-step", type=float, metavar="SECONDS", help="as for `coopdrive service`")
    group.add_argument("-v", "--verbose", action="store_true")
    group.set_defaults(handler=_group)


def _service(args) -> int:
    from coopdrive.bus import BusConfig
    from coopdrive.runtime.config import load_config
    from coopdrive.runtime.hardware_wait import run_waiting_for_hardware
    from coopdrive.runtime.launcher_watch import exit_with_launcher
    from coopdrive.runtime.priority import lower_cpu_priority
    from coopdrive.runtime.registry import service_class
    from coopdrive.runtime.runner import ClockMode, ServiceRunner

    try:
        cls = service_class(args.name)
    except KeyError as error:
        print(f"coopdrive: {error.args[0]}", file=sys.stderr)
        return EXIT_USAGE
    config = load_config(cls.Config, args.config, args.set)
    exit_with_launcher()
    if config.cpu_nice:
        lower_cpu_priority(config.cpu_nice)  # before the bus opens its threads, which inherit it
    bus = BusConfig(connect=args.connect, listen=args.listen or ["tcp/127.0.0.1:0"],
                    zenoh_config_file=str(args.zenoh_config) if args.zenoh_config else None)
    if args.hardware_retry is not None and args.hardware_retry <= 0:
        raise ConfigError(f"--hardware-retry {args.hardware_retry:g}: a time in seconds above 0")
    run_waiting_for_hardware(
        lambda: ServiceRunner(cls, config, args.vehicle, bus, ClockMode(args.clock), clock_step_s=args.clock_step),
        args.hardware_retry, f"{args.vehicle}/{args.name}")
    return EXIT_OK


def _group(args) -> int:
    from coopdrive.bus import BusConfig
    from coopdrive.runtime.config import ConfigError, validate_config
    from coopdrive.runtime.group import GroupMember, ServiceGroup
    from coopdrive.runtime.launcher_watch import exit_with_launcher
    from coopdrive.runtime.registry import service_class
    from coopdrive.runtime.runner import ClockMode

    try:
        entries = json.loads(args.spec.read_text())
        members = []
        for index, entry in enumerate(entries):
            cls = service_class(entry["service"])
            members.append(GroupMember(cls, validate_config(cls.Config, entry.get("config", {}),
                                                            f"{args.spec}[{index}]"), entry.get("vehicle", "ego")))
    except (OSError, ValueError, KeyError, TypeError) as error:
        raise ConfigError(f"{args.spec}: {error.args[0] if error.args else error}") from None
    exit_with_launcher()
    bus = BusConfig(connect=args.connect, listen=args.listen or ["tcp/127.0.0.1:0"])
    group = ServiceGroup(members, bus, ClockMode(args.clock), clock_step_s=args.clock_step)
    group.run()
    return EXIT_FAILED if group.failed else EXIT_OK
