"""Issue 72's acceptance run, `coopdrive run sumo-motorway --seed 1`, once for every test here: four stacks platoon in
the right lane of the shipped motorway (scenarios/sumo/, SUMO's own tools made it) among over a hundred SUMO cars and
trucks, the on-ramp's merging in at the junction behind them. The run passes with no collision with any SUMO vehicle,
the stacks saw SUMO's vehicles, and the summary says what SUMO counted of its drivers' reactions."""

import json
import subprocess
import sys

import pytest

from tests.scenario_report import FASTEST_LAYOUT, RUN_TIMEOUT_S

pytestmark = pytest.mark.whole_run
# The run's 12 simulated seconds, in whichever test comes first, may take longer than a test's 300 s on a loaded
# 2-core machine (its 20 s took 5 minutes beside four other jobs).
RUN_LONG = pytest.mark.timeout(RUN_TIMEOUT_S)

# Issue 72's acceptance: 100 or more SUMO vehicles in the run.
SUMO_VEHICLES = 100


@pytest.fixture(scope="module")
def summary():
    result = subprocess.run([sys.executable, "-m", "coopdrive.cli", "run", "sumo-motorway", "--seed", "1", "--json",
                             *FASTEST_LAYOUT], capture_output=True, text=True, timeout=RUN_TIMEOUT_S)
    assert result.returncode == 0, result.stdout[-2000:] + result.stderr[-2000:]
    return json.loads(result.stdout)


@RUN_LONG
def test_the_platoon_passes_among_a_hundred_sumo_vehicles_without_a_collision_with_any(summary):
    assert summary["scenario"] == "sumo-motorway" and summary["success"] is True
    assert summary["sumo_vehicles"] >= SUMO_VEHICLES
    assert summary["collisions"] == 0 and summary["sumo_collisions_with_ours"] == 0 and summary["sumo_collisions"] == 0


@RUN_LONG
def test_the_platoon_keeps_its_gaps_among_sumo_s_cars(summary):
    # A SUMO car may close up to SUMO's own minimum gap (2.5 m) behind the platoon's last car, not to ours; the docs
    # state the platoon's spacing error under 2 m (0.82 m at most with seed 1).
    assert summary["min_gap_m"] > 2.0
    assert summary["spacing_error_max_m"] < 2.0


@RUN_LONG
def test_the_summary_reports_sumo_s_vehicles_the_stacks_saw_and_sumo_s_count_of_their_reactions(summary):
    assert 1 <= summary["sumo_vehicles_seen"] <= summary["sumo_vehicles"]
    for key in ("sumo_emergency_braking", "sumo_emergency_stops", "sumo_teleports"):
        assert summary[key] >= 0
