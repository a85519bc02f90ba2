#!/usr/bin/env bash
# CI's sweep (.ci/run; issue 26): seeds 1-2 of every scenario (SEEDS), without reports, in the seconds CI has left
# (the argument), through tools/sweep.sh. About 8 minutes of both cores in a normal hour. A run that fails fails CI.
# With its time limit the sweep runs every scenario's seed 1 before any seed 2 (the cheapest first within a seed),
# so a slower hour loses seed-2 runs (whichever the limit finds unfinished) before any scenario's seed 1, and a
# seed's long scenarios before its short ones. The runs it does not finish are listed in the pass table and do not
# fail CI (the sweep's exit status 4). With under a minute left the sweep is skipped, and says so.
# BESIDE=1: the sweep runs beside other work (a test suite, as .ci/run once ran it), behind it, in the cores it
# leaves idle and then in all of them. The script must then lead a session of its own (`setsid`): it sets that
# session's nice value to 19 and has every session its runs start do the same (COOPDRIVE_SESSION_NICE), since Linux
# shares the cores between sessions (autogroups) before it looks at a thread's nice value. Its threads get nice 19
# too (what counts on a kernel without autogroups) and the idle scheduling policy, SCHED_IDLE, so that a test's
# thread that wakes takes the core from them at once: with nice alone the suite took up to a tenth longer beside it.
set -uo pipefail
cd "$(dirname "$0")/.."
left_s=${1:?usage: tools/ci_sweep.sh SECONDS_LEFT}
if [ "$left_s" -lt 60 ]; then
  echo "CI sweep skipped: ${left_s} s of CI's time left"
  exit 0
fi
behind=()
if [ "${BESIDE:-0}" = 1 ]; then
  read -r -a stat < "/proc/$$/stat"
  if [ "${stat[5]}" != "$$" ]; then
    echo "tools/ci_sweep.sh: BESIDE=1 lowers its whole session's priority, so it must lead one of its own (setsid)" >&2
    exit 2
  fi
  echo 19 2>/dev/null > /proc/self/autogroup || true  # no autogroups: the threads' nice values decide
  export COOPDRIVE_SESSION_NICE=19
  behind=(nice -n 19)
  if chrt --idle 0 true 2>/dev/null; then
    behind=(chrt --idle 0 nice -n 19)
  fi
fi
status=0
SEEDS=${SEEDS:-1-2} REPORTS=0 OUT=${OUT:-out/ci-sweep} TIME_LIMIT=$left_s "${behind[@]}" tools/sweep.sh || status=$?
if [ "$status" -eq 4 ]; then
  echo "CI sweep: stopped after ${left_s} s with runs not finished (listed above); every run that finished passed"
  exit 0
fi
exit "$status"
