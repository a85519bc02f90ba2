"""The v2x command line: `coopdrive v2x decode|send|replay ...` and `coopdrive pki init ...` (add_pki_commands).

Arguments are parsed and results printed here; the work is done by the module each command is named for
(capture_decode.py, send_file.py, capture_player.py, coopdrive/v2x/security/pki.py), imported only when its command runs so
that every other `coopdrive` command starts without the codec.
"""

from __future__ import annotations

import argparse
import os
import sys
from pathlib import Path

from coopdrive.exit_status import EXIT_FAILED, EXIT_OK, EXIT_USAGE


def add_commands(commands):
    """Adds `v2x` and its subcommands; returns its subcommands, for the application to add those of other
    services (the planner's `advise`)."""
    v2x = commands.add_parser("v2x", help="V2X tools: decode captures, inject messages")
    v2x_commands = v2x.add_subparsers(dest="v2x_command", required=True)
    decode = v2x_commands.add_parser("decode", help="print every frame of a pcap or pcapng capture, and a summary")
    decode.add_argument("file", type=Path)
    decode.add_argument("--json", action="store_true", help="one JSON object per frame, then {\"summary\": ...}")
    decode.add_argument("--trust", type=Path, action="append", default=[], metavar="FILE_OR_DIR",
                        help="root / authority certificates (COER) to trust; a directory: its .cert/.oer/.coer files")
    decode.add_argument("--no-freshness", action="store_true",
                        help="do not judge generation times against the capture's timestamps")
    decode.add_argument("--pki", type=Path, help=argparse.SUPPRESS)  # older name of --trust PKI_DIR
    decode.set_defaults(handler=_decode)
    send = v2x_commands.add_parser("send", help="send one CAM/DENM/iCLCM described in YAML to a radio box")
    send.add_argument("file", type=Path)
    send.add_argument("--address", default="127.0.0.1")
    send.add_argument("--port", type=int, default=4401)
    send.set_defaults(handler=_send)
    replay = v2x_commands.add_parser("replay", help="send a capture's GN packets at their pace to a radio-box UDP port "
                                                    "or onto a network interface")
    replay.add_argument("file", type=Path)
    replay.add_argument("--address", default="127.0.0.1")
    replay.add_argument("--port", type=int, default=4401, help="the v2x service's listen port (link.listen_port)")
    replay.add_argument("--interface", help="send onto this network interface instead (an OCB interface: Ethernet "
                                            "frames of ethertype 0x8947 from each sender's MAC; needs CAP_NET_RAW)")
    replay.add_argument("--rate", type=float, default=1.0, help="pace: 2.0 sends twice as fast as recorded")
    replay.set_defaults(handler=_replay)
    return v2x_commands


def add_pki_commands(pki_commands) -> None:
    """`coopdrive pki init`, under the `pki` command the deployment commands make (coopdrive/cli_deploy.py)."""
    init = pki_commands.add_parser("init", help="a test PKI for signed V2X (ETSI TS 103 097): a root CA, an "
                                                "authorisation authority and tickets")
    init.add_argument("directory", type=Path)
    init.add_argument("--vehicles", nargs="+", default=["ego", "leader"])
    init.set_defaults(handler=_pki_init)


def _decode(args: argparse.Namespace) -> int:
    from coopdrive.recording.capture import CaptureFormatError
    from coopdrive.services.v2x.capture_decode import decode_capture
    from coopdrive.v2x.security.trust import TrustFileError

    try:
        for line in decode_capture(args.file, as_json=args.json, trust=[*args.trust, *filter(None, [args.pki])],
                                   freshness=not args.no_freshness):
            print(line)
    except BrokenPipeError:  # `coopdrive v2x decode F | head`: the reader has seen enough
        os.dup2(os.open(os.devnull, os.O_WRONLY), sys.stdout.fileno())
        return EXIT_OK
    except (OSError, CaptureFormatError, TrustFileError) as error:
        print(f"coopdrive: {args.file}: {error}", file=sys.stderr)
        return EXIT_USAGE
    return EXIT_OK


def _send(args: argparse.Namespace) -> int:
    from coopdrive.services.v2x.send_file import send_from_yaml

    message_id = send_from_yaml(args.file, args.address, args.port)
    print(f"sent {message_id.name} to {args.address}:{args.port}")
    return EXIT_OK


def _replay(args: argparse.Namespace) -> int:
    from coopdrive.runtime.service import HardwareUnavailable
    from coopdrive.services.v2x.capture_player import RawSink, ReplayError, UdpSink, replay_capture

    try:
        sink = RawSink(args.interface) if args.interface else UdpSink((args.address, args.port))
        summary = replay_capture(args.file, sink, args.rate)
    except (OSError, ReplayError, HardwareUnavailable) as error:
        print(f"coopdrive: {error}", file=sys.stderr)
        return EXIT_USAGE
    skipped = ", ".join(f"{count} {why}" for why, count in sorted(summary.skipped.items()))
    target = f"onto {args.interface}" if args.interface else f"to {args.address}:{args.port}"
    print(f"sent {summary.sent} GN packets {target} in {summary.duration_s:.2f} s"
          + (f"; skipped frames: {skipped}" if skipped else "")
          + (f"; {summary.send_errors} send errors" if summary.send_errors else ""))
    return EXIT_OK if summary.send_errors == 0 else EXIT_FAILED


def _pki_init(args: argparse.Namespace) -> int:
    from coopdrive.v2x.security.pki import pki_init

    return pki_init(args.directory, args.vehicles)
