"""`coopdrive v2x advise CAPTURE ...`: what the planner's traffic lights would have advised on a capture's MAPEMs and
SPATEMs (desk_advice.py), imported only when the command runs."""

from __future__ import annotations

import argparse
import json
import math
import sys
from pathlib import Path

from coopdrive.exit_status import EXIT_OK, EXIT_USAGE


def add_v2x_commands(v2x_commands) -> None:
    advise = v2x_commands.add_parser(
        "advise", help="what the planner would have advised at a traffic light, step by step over a capture's SPATEMs")
    advise.add_argument("file", type=Path)
    pose = advise.add_argument_group("an ego pose, matched to the capture's MAPEM lanes")
    pose.add_argument("--lat", type=float, help="ego latitude (degrees)")
    pose.add_argument("--lon", type=float, help="ego longitude (degrees)")
    pose.add_argument("--heading", type=float, default=0.0,
                      help="ego heading, degrees clockwise from north (as a compass)")
    pose.add_argument("--intention", choices=["straight", "left", "right"], default="straight")
    group = advise.add_argument_group("or, without a MAPEM, a signal group and the distance to its stop line")
    group.add_argument("--intersection", type=int, help="intersection id")
    group.add_argument("--group", type=int, help="signal group")
    group.add_argument("--distance", type=float, help="metres from the front bumper to the stop line")
    advise.add_argument("--speed", type=float, default=13.9, help="ego speed (m/s)")
    advise.add_argument("--limit", type=float, default=13.9, help="the road's speed limit (m/s)")
    advise.add_argument("--no-glosa", dest="glosa", action="store_false", help="stop on red without GLOSA")
    advise.add_argument("--json", action="store_true", help="one JSON object per SPATEM")
    advise.set_defaults(handler=_advise)


def _target(args: argparse.Namespace):
    from coopdrive.services.planner.config import Intention
    from coopdrive.services.planner.desk_advice import EgoPose, GroupApproach

    if args.lat is not None and args.lon is not None:
        # Compass heading (clockwise from north) to the ENU yaw the planner uses (counter-clockwise from east).
        yaw_rad = math.radians(90.0 - args.heading)
        return EgoPose(args.lat, args.lon, yaw_rad, args.speed, Intention[args.intention.upper()])
    if None not in (args.intersection, args.group, args.distance):
        return GroupApproach(args.intersection, args.group, args.distance, args.speed)
    return None


def _advise(args: argparse.Namespace) -> int:
    from coopdrive.recording.capture import CaptureFormatError
    from coopdrive.services.planner.desk_advice import advise_capture, format_advice

    target = _target(args)
    if target is None:
        print("coopdrive: v2x advise needs --lat and --lon, or --intersection, --group and --distance",
              file=sys.stderr)
        return EXIT_USAGE
    try:
        for record in advise_capture(args.file, target, args.limit, args.glosa):
            print(json.dumps(record) if args.json else format_advice(record))
    except (OSError, CaptureFormatError) as error:
        print(f"coopdrive: {args.file}: {error}", file=sys.stderr)
        return EXIT_USAGE
    return EXIT_OK
