#!/usr/bin/env bash
# The sweep of issue 26: every scenario on seeds 1-20 (or SEEDS), real-world defaults, two runs at a time
# (WORKERS), results in OUT (default out/sweep): summary.json, summary.csv and the pass table pass_table.md.
# FAULTS=FILE sweeps its fault variants too (docs/sweep-faults.yaml); CLUSTER=tcp://host:8786 runs on that Dask
# scheduler's workers instead of a local cluster (docs/how-to/sweeps.md); SCENARIO=NAME sweeps that scenario alone.
# REPORTS=0 keeps each run's metrics.json and the summaries only, no recording or plots (CI's sweep, .ci/run).
# TIME_LIMIT=SECONDS stops the sweep that long after it started (its cluster's start counted) and lists the runs it
# left: exit status 4 when every run that finished passed. DURATION=SECONDS runs each scenario that long instead of
# its own duration (a quick look, not the sweep of the issue).
# On two cores this takes hours; `SEEDS=1-2 tools/sweep.sh` is the quick check.
# Prints the pass table and exits non-zero when any run failed (or the sweep could not start).
# PYTHON: the interpreter with coopdrive installed (default .venv/bin/python, as `make` sets it up).
set -uo pipefail
cd "$(dirname "$0")/.."
seeds=${SEEDS:-1-20}
out=${OUT:-out/sweep}
rm -f "$out/pass_table.md"  # a table printed below is this sweep's, never an earlier one's
"${PYTHON:-.venv/bin/python}" -m coopdrive.cli run "${SCENARIO:-all}" --seeds "$seeds" --workers "${WORKERS:-2}" \
  --out "$out" ${FAULTS:+--faults "$FAULTS"} $([ "${REPORTS:-1}" = 0 ] && echo --no-reports) \
  ${TIME_LIMIT:+--time-limit "$TIME_LIMIT"} ${DURATION:+--duration "$DURATION"} ${CLUSTER:+--cluster "$CLUSTER"}
status=$?
if [ -f "$out/pass_table.md" ]; then
  cat "$out/pass_table.md"
fi
exit $status
