#!/usr/bin/env bash
# The live V2X exchange at a desk, on a real interface (docs/how-to/v2x-live.md): our v2x service on a raw link
# (GN frames, ethertype 0x8947) on INTERFACE sends CAMs and a DENM for 30 s and says what it heard and refused;
# with --flexstack-interface, FlexStack 0.11.2 (from .venv-peers, made here if missing) runs on a second interface.
#
#   tools/v2x_live_peer.sh --interface wlan1                               # against whatever is on the air
#   tools/v2x_live_peer.sh --interface wlan1 --flexstack-interface wlan2   # against FlexStack on a second card
#   tools/v2x_live_peer.sh --interface wlan1 --duration-s 60 --json        # longer, with the full summaries
#
# Needs CAP_NET_RAW (root, or setcap cap_net_raw+ep on .venv's python) and an interface already set up for OCB
# (channel 180, 10 MHz: `iw dev wlan1 set type ocb; ip link set wlan1 up; iw dev wlan1 ocb join 5900 10MHZ`).
# The CI test of the same exchange runs between two network namespaces: tests/v2x/live/test_flexstack_live.py.
set -euo pipefail
cd "$(dirname "$0")/.."
for argument in "$@"; do
  [ "$argument" = "--flexstack-interface" ] && tools/peer_env.sh
done
exec .venv/bin/python -m tests.v2x.live.desk "$@"
