"""The `coopdrive` commands that judge and analyse what was run: score, analyze, scenarios and candump. One add_*
function for their parsers, one handler each."""

from __future__ import annotations

import json
import sys
from pathlib import Path

from coopdrive.exit_status import EXIT_OK, EXIT_USAGE


def add_commands(commands) -> None:
    score = commands.add_parser("score", help="judge a recording from its ground truth")
    score.add_argument("file", type=Path, help="a run's recording (FILE.mcap, with its ground truth)")
    score.add_argument("--scenario", help="judging settings of this scenario (default: the recorded one)")
    score.add_argument("--json", action="store_true", help="print the metrics as JSON")
    score.add_argument("--reference", type=Path, metavar="REF.csv",
                       help="judge a replay's ego/state (and its fixes) against this reference trajectory instead: "
                            "CSV of time, lat, lon[, heading, speed]")
    score.add_argument("--standstill", action="store_true",
                       help="judge a replay's ego/state (and its fixes) against the mean of the recording's own fixes "
                            "instead, for a receiver that stood still: the estimate's claimed accuracy against its "
                            "scatter (the options of --reference apply)")
    score.add_argument("--vehicle", default="ego", help="with --reference: whose estimate (default: ego)")
    score.add_argument("--lever-arm", metavar="X,Y", help="with --reference: the compared point, metres ahead of "
                                                          "and left of the rear axle (default: the GNSS antenna of "
                                                          "the recorded geolocation config)")
    score.add_argument("--max-offset", type=float, default=0.5, metavar="SECONDS",
                       help="with --reference: search the best-fit time offset within +-this (default: 0.5)")
    score.add_argument("--out", type=Path, metavar="FILE.json", help="with --reference: write the figures here")
    score.add_argument("--report", type=Path, metavar="DIR", help="with --reference: a page (DIR/index.html) with the "
                                                                  "errors over time inside the 2-sigma bounds")
    score.set_defaults(handler=_score)

    analyze = commands.add_parser("analyze", help="analyses of controllers and runs")
    analyses = analyze.add_subparsers(dest="analysis", required=True)
    string = analyses.add_parser("string", help="predicted string gain per following law, beside a measured run")
    string.add_argument("--law", action="append", dest="laws", metavar="LAW",
                        help=f"one of {', '.join(law.value for law in _following_laws())} (default: all)")
    string.add_argument("--profile", default="car", help="vehicle profile: car or truck")
    string.add_argument("--time-gap", type=float, help="time gap h in s (default: the profile's)")
    string.add_argument("--comm-delay", type=float, default=0.1, help="V2V delay in s")
    string.add_argument("--recording", type=Path, metavar="FILE.mcap", help="a recorded string run to measure")
    string.add_argument("--out", type=Path, metavar="DIR", help="write the Bode plot here")
    string.add_argument("--json", action="store_true", help="print the figures as JSON")
    string.set_defaults(handler=_analyze_string)

    scenarios = commands.add_parser("scenarios", help="list the scenarios with a one-line description")
    scenarios.set_defaults(handler=_scenarios)

    candump = commands.add_parser("candump", help="a vehicle's CAN frames from a recording, as a candump .log")
    candump.add_argument("file", type=Path, help="the recording (FILE.mcap)")
    candump.add_argument("--vehicle", default="ego", help="whose CAN bus (default: ego)")
    candump.add_argument("--out", type=Path, required=True, metavar="FILE.log", help="the candump log to write")
    candump.set_defaults(handler=_candump)


def _following_laws():
    from coopdrive.services.control.string_stability import FollowingLaw

    return list(FollowingLaw)


def _analyze_string(args) -> int:
    from rich.console import Console

    from coopdrive.analysis.string_command import StringAnalysisOptions, analyze_string
    from coopdrive.judging.score import ScoreError
    from coopdrive.services.control.string_stability import FollowingLaw

    try:
        laws = [FollowingLaw(name) for name in args.laws] if args.laws else list(FollowingLaw)
        options = StringAnalysisOptions(laws, args.profile, args.time_gap, args.comm_delay, args.recording, args.out)
        figures = analyze_string(options, Console(stderr=args.json))
    except (ValueError, ScoreError, OSError) as error:
        print(f"coopdrive: analyze string: {error}", file=sys.stderr)
        return EXIT_USAGE
    if args.json:
        print(json.dumps(figures, indent=2))
    return EXIT_OK


def _score(args) -> int:
    from coopdrive.judging.commands import score_command

    if args.reference is not None and args.standstill:
        print("coopdrive: score: --reference and --standstill: give one of them", file=sys.stderr)
        return EXIT_USAGE
    if args.reference is not None or args.standstill:
        return _score_reference(args)
    return score_command(args.file, args.json, args.scenario)


def _score_reference(args) -> int:
    from coopdrive.judging.reference_command import ReferenceRequest, reference_score_command
    from coopdrive.services.geolocation.frames import LeverArm

    lever_arm = None
    if args.lever_arm is not None:
        try:
            lever_arm = LeverArm(*(float(part) for part in args.lever_arm.split(",", 1)))
        except ValueError:
            print(f"coopdrive: score: --lever-arm {args.lever_arm!r}: expected X,Y in metres, e.g. 1.2,0",
                  file=sys.stderr)
            return EXIT_USAGE
    if args.max_offset < 0.0:
        print(f"coopdrive: score: --max-offset {args.max_offset:g}: a search range is 0 s or more", file=sys.stderr)
        return EXIT_USAGE
    return reference_score_command(ReferenceRequest(args.file, args.reference, args.vehicle, lever_arm,
                                                    args.max_offset, args.out, args.json, args.report))


def _scenarios(args) -> int:
    from coopdrive.judging.commands import scenarios_command

    return scenarios_command()


def _candump(args) -> int:
    from coopdrive.recording.candump_export import CandumpExportError, export_candump

    try:
        count = export_candump(args.file, args.vehicle, args.out)
    except (CandumpExportError, ValueError) as error:
        print(f"coopdrive: {error}", file=sys.stderr)
        return EXIT_USAGE
    print(f"{count} frames of {args.vehicle} to {args.out}")
    return EXIT_OK
