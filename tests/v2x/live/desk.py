"""The live exchange at a desk, on real interfaces (tools/v2x_live_peer.sh runs it; docs/how-to/v2x-live.md):
our v2x service on a raw link on --interface (an 802.11p OCB interface, a Cohda-style box's Linux interface), for
--duration-s, sending CAMs and a DENM and reporting what it heard; with --flexstack-interface, a FlexStack station
on that interface too (a second card: a packet socket does not hear frames sent from its own interface by another
socket as received ones). Prints what each station heard, then the full summaries as JSON with --json.
"""

from __future__ import annotations

import argparse
import json
import sys
import tempfile
from pathlib import Path

from coopdrive.services.v2x.config import V2xConfig
from tests.v2x.live.exchange import ExchangeError, run_exchange
from tests.v2x.live.stations import PEER_PYTHON, flexstack_station, our_config, our_station

DESK_DURATION_S = 30.0
FLEXSTACK_ID, FLEXSTACK_MAC = 4242, "02:00:00:00:42:42"


def heard_lines(name: str, summary: dict) -> list[str]:
    lines = [f"{name}: CAMs from {station}: {heard['count']} at {heard['speed_mps']} m/s"
             for station, heard in summary.get("cams", {}).items()]
    lines += [f"{name}: DENMs from {station}: {heard['count']}" for station, heard in summary.get("denms", {}).items()]
    refused = summary.get("status", {}).get("rejected_by_reason") or summary.get("verify_reports") or {}
    lines += [f"{name}: refused {count} as {reason}" for reason, count in refused.items()]
    return lines or [f"{name}: heard nothing"]


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--interface", required=True, help="our service's interface, e.g. wlan1 (CAP_NET_RAW)")
    parser.add_argument("--flexstack-interface", help="also run FlexStack (tools/peer_env.sh) on this interface")
    parser.add_argument("--duration-s", type=float, default=DESK_DURATION_S)
    parser.add_argument("--station-id", type=int, default=1001)
    parser.add_argument("--mac", default="02:00:00:00:10:01", help="our GN source MAC")
    parser.add_argument("--json", action="store_true", help="also print every station's full summary")
    args = parser.parse_args()
    if args.flexstack_interface and not PEER_PYTHON.is_file():
        sys.exit(f"v2x live: no {PEER_PYTHON} for FlexStack: run tools/peer_env.sh first")
    with tempfile.TemporaryDirectory(prefix="v2x-live-") as folder:
        config = our_config(Path(folder), args.interface, args.station_id, args.mac)
        stations = {"ours": our_station(config, "--denm", duration_s=args.duration_s)}
        if args.flexstack_interface:
            stations["flexstack"] = flexstack_station(args.flexstack_interface, FLEXSTACK_ID, FLEXSTACK_MAC,
                                                      "--denm", duration_s=args.duration_s)
        print(f"v2x live: our station {args.station_id} on {args.interface} (profile {V2xConfig().profile.value}) for "
              f"{args.duration_s:.0f} s", file=sys.stderr)
        try:
            summaries = run_exchange(stations, Path(folder))
        except ExchangeError as error:
            sys.exit(f"v2x live: {error}")
    ours = summaries["ours"]
    if ours["service_exited_early"] or not ours["started"]:
        sys.exit(f"v2x live: our service stopped: {(ours['service_stderr'].splitlines() or ['no message'])[-1]}")
    for name, summary in summaries.items():
        print("\n".join(heard_lines(name, summary)))
    if args.json:
        print(json.dumps(summaries, indent=1))


if __name__ == "__main__":
    main()
