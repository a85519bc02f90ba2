"""`coopdrive run SCENARIO --v2v-loss P --v2v-cut-at S`: faults a user adds to a scenario without editing it."""

import subprocess
import sys
from pathlib import Path

import pytest

from coopdrive.launch.run import RunOptions, build_specs
from coopdrive.services.sim.fault_config import V2vLoss
from coopdrive.services.sim.scenario_config import ScenarioError, load_scenario

EXAMPLE = Path(__file__).parents[2] / "services" / "sim" / "examples" / "string_stability.yaml"
LOSSY = ({"type": "v2v_loss", "start_s": 0.0, "loss_probability": 0.2},
         {"type": "v2v_loss", "start_s": 30.0, "loss_probability": 1.0})


def sim_config(tmp_path, **options):
    specs = build_specs(RunOptions(scenario=str(EXAMPLE), stacks=1, **options), tmp_path)
    return next(spec.config for spec in specs if spec.service == "sim")


def test_added_faults_come_after_the_scenarios_own_in_the_file_the_simulator_loads(tmp_path):
    scenario = load_scenario(sim_config(tmp_path, extra_faults=LOSSY)["scenario_file"])
    losses = [f for f in scenario.faults if isinstance(f, V2vLoss)]
    assert [(f.vehicle_id, f.start_s, f.loss_probability) for f in losses] == [
        ("ego", 40.0, 1.0), (None, 0.0, 0.2), (None, 30.0, 1.0)]
    assert scenario.name == "string_stability"


def test_without_added_faults_the_packaged_file_is_used_as_it_is(tmp_path):
    assert sim_config(tmp_path)["scenario_file"] == str(EXAMPLE.resolve())


def test_the_built_in_world_refuses_faults_for_want_of_a_radio(tmp_path):
    with pytest.raises(ScenarioError, match="faults need a scenario file run"):
        build_specs(RunOptions(scenario="follow", extra_faults=LOSSY), tmp_path)


@pytest.mark.parametrize("flag, value, message", [
    ("--v2v-loss", "1.5", "--v2v-loss 1.5: a probability from 0 to 1"),
    ("--v2v-cut-at", "-2", "--v2v-cut-at -2.0: a time from the start of the run"),
])
def test_an_out_of_range_fault_flag_is_refused_naming_it(flag, value, message):
    completed = subprocess.run([sys.executable, "-m", "coopdrive.cli", "run", "string", flag, value],
                               capture_output=True, text=True, timeout=60)
    assert completed.returncode == 2
    assert message in completed.stderr
