"""The recording commands of `coopdrive`: record, import, replay, export. One add_* function per command."""

from __future__ import annotations

import argparse
import json
import struct
import sys
from pathlib import Path

from coopdrive.exit_status import EXIT_FAILED, EXIT_OK, EXIT_USAGE


def add_commands(commands) -> None:
    add_record_command(commands)
    add_import_command(commands)
    add_replay_command(commands)
    add_export_command(commands)


def add_record_command(commands) -> None:
    record = commands.add_parser("record", help="record a live bus to MCAP (with every service's config) until Ctrl-C")
    record.add_argument("file", help="FILE.mcap, or a folder (ending in /) for drive-<UTC time>.mcap")
    record.add_argument("--connect", action="append", default=[])
    record.add_argument("--key", help="what to record (default: coopdrive/** or, with --vehicle, its topics)")
    record.add_argument("--vehicle", help="only this vehicle's topics and services' configs (what its bus "
                                          "credentials may read)")
    record.add_argument("--zenoh-config", type=Path, help="Zenoh JSON5 config, e.g. an observer's bus credentials")
    record.add_argument("--duration", type=float, metavar="SECONDS", help="stop after this long")
    record.set_defaults(handler=_record)


def _record(args) -> int:
    from coopdrive.launch.live_record import record_live

    key = args.key or (f"coopdrive/{args.vehicle}/**" if args.vehicle else "coopdrive/**")
    recording = record_live(args.file, args.connect, key, args.duration,
                            str(args.zenoh_config) if args.zenoh_config else None, args.vehicle or "*")
    print(f"recorded {recording.messages} messages to {recording.path}; configs of: "
          f"{', '.join(recording.services) or 'no service'}")
    if recording.failure is not None:
        print(f"coopdrive: record: {recording.path}: stopped early: {recording.failure}", file=sys.stderr)
        return EXIT_FAILED
    return EXIT_OK


class _CandumpAction(argparse.Action):
    """--candump FILE appends (FILE, "vehicle"); --can-bus NAME names the bus of the --candump before it."""

    def __call__(self, parser, namespace, value, option_string=None):
        logs = getattr(namespace, "candump", None) or []
        if option_string == "--candump":
            logs.append((Path(value), "vehicle"))
        elif not logs:
            parser.error("--can-bus names the bus of the --candump FILE given before it")
        else:
            logs[-1] = (logs[-1][0], value)
        namespace.candump = logs


def add_import_command(commands) -> None:
    imports = commands.add_parser("import", help="turn NMEA, candump and pcap logs into a recording replay takes")
    imports.add_argument("--out", type=Path, required=True, metavar="DRIVE.mcap")
    imports.add_argument("--vehicle", default="ego", help="vehicle id of the recording (default: ego)")
    imports.add_argument("--nmea", action="append", default=[], type=Path, metavar="FILE",
                         help="a GNSS receiver's NMEA log, on topic gnss/nmea")
    imports.add_argument("--nmea-rate", type=float, metavar="HZ", help="epochs per second of NMEA logs without UTC")
    imports.add_argument("--candump", action=_CandumpAction, default=[], metavar="FILE",
                         help="a `candump -l` log, on topic can/vehicle")
    imports.add_argument("--can-bus", action=_CandumpAction, dest="candump", metavar="NAME",
                         help="the previous --candump goes on can/NAME instead")
    imports.add_argument("--pcap", action="append", default=[], type=Path, metavar="FILE",
                         help="a V2X capture (pcap or pcapng), on topic v2x/rx")
    imports.add_argument("--offset", action="append", default=[], metavar="NAME=SECONDS",
                         help="shift a log's times (NAME: nmea, candump, pcap or the file's name)")
    imports.add_argument("--json", action="store_true", help="print the summary as JSON")
    imports.set_defaults(handler=_import)


def _import(args) -> int:
    from coopdrive.recording.import_source import ImportFailure
    from coopdrive.recording.importer import ImportRequest, import_logs

    try:
        request = ImportRequest(args.out, args.vehicle, args.nmea, args.candump, args.pcap,
                                _offsets(args.offset), args.nmea_rate)
        result = import_logs(request)
    except (ImportFailure, OSError) as error:
        print(f"coopdrive: import: {error}", file=sys.stderr)
        return EXIT_USAGE
    if args.json:
        print(json.dumps({"out": str(result.out), "messages": result.messages, "warnings": result.warnings,
                          "sources": [source.as_dict() for source in result.sources]}, indent=2))
    else:
        print("\n".join(result.summary_lines()))
    return EXIT_OK


def _offsets(assignments: list[str]) -> dict[str, float]:
    from coopdrive.recording.import_source import ImportFailure

    offsets = {}
    for text in assignments:
        name, _, seconds = text.partition("=")
        try:
            offsets[name] = float(seconds)
        except ValueError:
            raise ImportFailure(f"--offset {text!r}: expected NAME=SECONDS, e.g. candump=1534758000") from None
    return offsets


def add_replay_command(commands) -> None:
    replay = commands.add_parser("replay", help="replay a recording through one service and compare its outputs")
    replay.add_argument("file", type=Path, help="the recording (FILE.mcap: a run's, a drive's or an import's)")
    replay.add_argument("--service", required=True, help="the service to run again on the recorded inputs, e.g. scene")
    replay.add_argument("--vehicle", help="whose service (default: the one vehicle the recording has it for)")
    replay.add_argument("--config", type=Path, help="replay with this config instead of the recorded one")
    replay.add_argument("--set", action="append", default=[], metavar="KEY=VALUE", help="change a config key")
    replay.add_argument("--out", type=Path, metavar="FILE.mcap", help="write the inputs and the replayed outputs")
    replay.add_argument("--report", type=Path, metavar="DIR", help="plot replayed against recorded outputs")
    replay.add_argument("--json", action="store_true", help="print the differences as JSON")
    replay.add_argument("--from", dest="from_s", type=float, metavar="SECONDS",
                        help="replay from this many seconds after the recording's first message (the service starts "
                             "there)")
    replay.add_argument("--to", dest="to_s", type=float, metavar="SECONDS",
                        help="replay up to this many seconds after the recording's first message")
    replay.set_defaults(handler=_replay)


def _replay(args) -> int:
    from mcap.exceptions import McapError

    from coopdrive.recording.reader import RecordingError
    from coopdrive.recording.replay import ReplayError, TimeWindow, replay_service
    from coopdrive.recording.replay_counts import replay_warnings
    from coopdrive.recording.replay_diff import compare_outputs
    from coopdrive.roadmap.sumo_network import SumoNetworkError

    try:
        window = None if args.from_s is None and args.to_s is None else TimeWindow(args.from_s or 0.0, args.to_s)
        result = replay_service(args.file, args.service, args.vehicle, args.out, args.config, args.set, window)
    except RecordingError as error:
        print(f"coopdrive: replay: {error}", file=sys.stderr)
        return EXIT_USAGE
    except SumoNetworkError as error:
        # A run on a SUMO network names its file: on another machine, or once moved, it is not there.
        print(f"coopdrive: replay: {args.file}: its map: {error}", file=sys.stderr)
        return EXIT_USAGE
    except (ReplayError, KeyError) as error:
        print(f"coopdrive: {error.args[0] if error.args else error}", file=sys.stderr)
        return EXIT_USAGE
    except (OSError, McapError, struct.error) as error:
        print(f"coopdrive: replay: {args.file}: not a readable MCAP recording ({error})", file=sys.stderr)
        return EXIT_USAGE
    differences = compare_outputs(result.outputs, result.recorded_outputs)
    warnings = replay_warnings(args.service, result.counters)
    summary = {"service": args.service, "mode": result.mode, "steps": result.steps, "outputs": len(result.outputs),
               "recorded_outputs": len(result.recorded_outputs), "notes": result.notes, "warnings": warnings,
               "counters": result.counters,
               "window_s": None if result.window is None else [result.window.from_s, result.window.to_s],
               "topics": [d.as_dict() for d in differences]}
    if args.report is not None:
        from coopdrive.recording.replay_plots import write_report

        write_report(args.report, result.outputs, result.recorded_outputs, differences, summary)
    exact = result.exact
    problems = result.mismatches() if exact else []
    if args.json:
        print(json.dumps({**summary, "identical": exact and not problems}, indent=2))
    else:
        _print_replay(args, result, differences, problems, exact)
    for warning in warnings:
        print(f"coopdrive: replay: warning: {warning}", file=sys.stderr)
    return EXIT_FAILED if problems else EXIT_OK


def _print_replay(args, result, differences, problems, exact: bool) -> None:
    from coopdrive.recording.replay_counts import counter_lines
    from coopdrive.recording.replay_diff import table

    where = f" to {args.out}" if args.out else ""
    print(f"replayed {result.steps} {'steps' if result.mode == 'lockstep' else 'inputs'} through {args.service} "
          f"({result.mode} clock): {len(result.outputs)} messages{where}")
    for note in result.notes:
        print(f"note: {note}")
    if exact and not problems:
        print("identical to the recorded outputs")
    else:
        if problems:
            print("differs from the recording: " + "; ".join(problems))
        print(table(differences))
        if args.report is not None:
            print(f"report: {args.report}")
    if result.counters:
        print(f"{args.service} counted:")
        print("\n".join(f"  {line}" for line in counter_lines(result.counters)))


def add_export_command(commands) -> None:
    export = commands.add_parser("export", help="one topic of a recording as CSV or JSON lines, or the recording "
                                                "with the channels Foxglove draws")
    export.add_argument("file", type=Path, help="the recording (FILE.mcap)")
    export.add_argument("--topic", help="the topic to write, e.g. ego/state (every vehicle's), or a vehicle's as "
                                        "VEHICLE/TOPIC, e.g. p2/scene")
    export.add_argument("--foxglove", type=Path, metavar="OUT.mcap",
                        help="write the recording with Foxglove's map, 3D and plot channels added")
    export.add_argument("--vehicle", help="only this vehicle's messages (default: every vehicle's)")
    export.add_argument("--format", choices=["csv", "jsonl"], default="csv",
                        help="one row per message with a column per field, or one JSON object per line (default: csv)")
    export.add_argument("--out", type=Path, help="file to write (default: standard output)")
    export.set_defaults(handler=_export)


def _export(args) -> int:
    from mcap.exceptions import McapError

    from coopdrive.recording.exporter import ExportError, export_rows, write_rows
    from coopdrive.recording.reader import RecordingError

    if (args.topic is None) == (args.foxglove is None):
        print("coopdrive: export: give either --topic TOPIC or --foxglove OUT.mcap", file=sys.stderr)
        return EXIT_USAGE
    if args.foxglove is not None:
        return _export_foxglove(args)
    try:
        rows = export_rows(args.file, args.topic, args.vehicle)
    except (ExportError, RecordingError, OSError, McapError, struct.error) as error:
        print(f"coopdrive: export: {error}", file=sys.stderr)
        return EXIT_USAGE
    if args.out is None:
        write_rows(rows, sys.stdout, args.format)
    else:
        with open(args.out, "w", newline="") as stream:
            write_rows(rows, stream, args.format)
        print(f"{len(rows)} rows of {args.topic} to {args.out}", file=sys.stderr)
    return EXIT_OK


def _export_foxglove(args) -> int:
    from mcap.exceptions import McapError

    from coopdrive.recording.foxglove_export import export_foxglove
    from coopdrive.recording.reader import RecordingError

    if args.foxglove.resolve() == args.file.resolve():
        print(f"coopdrive: export: --foxglove {args.foxglove}: write to another file than the recording read",
              file=sys.stderr)
        return EXIT_USAGE
    try:
        count = export_foxglove(args.file, args.foxglove)
    except RecordingError as error:
        print(f"coopdrive: export: {error}", file=sys.stderr)
        return EXIT_USAGE
    except (OSError, McapError, struct.error) as error:
        print(f"coopdrive: export: {args.file}: not a readable MCAP recording ({_one_line(error)})", file=sys.stderr)
        return EXIT_USAGE
    print(f"{count} messages with Foxglove's channels to {args.foxglove}", file=sys.stderr)
    return EXIT_OK


def _one_line(error: Exception) -> str:
    return " ".join(str(error).split())
