#!/usr/bin/env bash
# The peer stacks the live V2X tests run against (issues 71, 77), in their own virtual environment .venv-peers/:
# FlexStack (PyPI v2xflexstack, AGPL-3.0) is run only as a separate process by tests/v2x/live/, never imported by
# coopdrive's package, so it stays out of .venv and out of coopdrive's dependencies.
#
#   tools/peer_env.sh        create or update .venv-peers (idempotent: a stamp names the pinned versions)
#   PYTHON=python3.11 ...    the interpreter to build it with (default: python3, the one .venv is made with)
set -euo pipefail
cd "$(dirname "$0")/.."
PYTHON="${PYTHON:-python3}"
VENV=.venv-peers
# Pinned: the live tests assert this version's exact behaviour (docs/how-to/v2x-live.md).
PEERS="v2xflexstack==0.11.2"
STAMP="$VENV/.installed"

if [ -f "$STAMP" ] && [ "$(cat "$STAMP")" = "$PEERS" ] && [ -x "$VENV/bin/python" ]; then
  exit 0
fi
# A venv left half-made (interrupted while installing pip) is made again.
"$VENV/bin/python" -m pip --version >/dev/null 2>&1 || "$PYTHON" -m venv --clear "$VENV"
# shellcheck disable=SC2086  # PEERS is a list of requirements
"$VENV/bin/python" -m pip install --quiet $PEERS
echo "$PEERS" > "$STAMP"
