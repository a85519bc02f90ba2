#!/usr/bin/env bash
# The sweep of issue 26: every scenario on seeds 1-20 (or SEEDS), real-world defaults, two runs at a time
# (WORKERS), results in OUT (default out/sweep): summary.json, summary.csv and the pass table pass_table.md.
# FAULTS=FILE sweeps its fault variants too (docs/sweep-faults.yaml); CLUSTER=tcp://host:8786 runs on that Dask
# scheduler's workers instead of a local cluster (README, Sweeps).
# On two cores this takes hours; `SEEDS=1-2 tools/sweep.sh` is the quick check.
set -euo pipefail
cd "$(dirname "$0")/.."
seeds=${SEEDS:-1-20}
out=${OUT:-out/sweep}
.venv/bin/coopdrive run all --seeds "$seeds" --workers "${WORKERS:-2}" --out "$out" \
  ${FAULTS:+--faults "$FAULTS"} ${CLUSTER:+--cluster "$CLUSTER"} || true
cat "$out/pass_table.md"
