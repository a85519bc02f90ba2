#!/usr/bin/env bash
# The sweep of issue 26: every scenario on seeds 1-20 (or SEEDS), real-world defaults, two runs at a time
# (WORKERS), results in OUT (default out/sweep): summary.json, summary.csv and the pass table pass_table.md.
# On two cores this takes hours; `SEEDS=1-2 tools/sweep.sh` is the quick check.
set -euo pipefail
cd "$(dirname "$0")/.."
seeds=${SEEDS:-1-20}
out=${OUT:-out/sweep}
.venv/bin/coopdrive run all --seeds "$seeds" --workers "${WORKERS:-2}" --out "$out" || true
cat "$out/pass_table.md"
