"""`coopdrive run SCENARIO --v2v-loss P --v2v-cut-at S --fault YAML`: faults a user adds to a scenario without
editing it."""

import subprocess
import sys
from pathlib import Path

import pytest

from coopdrive.launch.run import RunOptions, build_specs
from coopdrive.services.sim.fault_config import V2vLoss
from coopdrive.services.sim.scenario_config import load_scenario

pytestmark = pytest.mark.whole_run

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


def test_follow_takes_added_faults_as_every_scenario_file_does(tmp_path):
    [sim] = [spec for spec in build_specs(RunOptions(scenario="follow", extra_faults=LOSSY), tmp_path)
             if spec.service == "sim"]
    assert "faults" in Path(sim.config["scenario_file"]).read_text()


@pytest.mark.parametrize("flag, value, message", [
    ("--v2v-loss", "1.5", "--v2v-loss 1.5: a probability from 0 to 1"),
    ("--v2v-cut-at", "-2", "--v2v-cut-at -2.0: a time from the start of the run"),
])
def test_an_out_of_range_fault_flag_is_refused_naming_it(flag, value, message):
    completed = subprocess.run([sys.executable, "-m", "coopdrive.cli", "run", "string", flag, value],
                               capture_output=True, text=True, timeout=60)
    assert completed.returncode == 2
    assert message in completed.stderr


@pytest.mark.parametrize("fault, message", [
    ("{type: iclcm_drop, vehicle_id: a2, flag: nope, start_s: 0}", "faults.0.flag: Input should be 'forward_id'"),
    ("[1", "--fault '[1': not YAML"),
    ("gnss_outage", "--fault 'gnss_outage': a mapping"),
])
def test_a_bad_fault_is_refused_in_one_line_naming_what_is_wrong_and_nothing_starts(fault, message):
    completed = subprocess.run([sys.executable, "-m", "coopdrive.cli", "run", "merge", "--fault", fault],
                               capture_output=True, text=True, timeout=60)
    assert completed.returncode == 2
    assert message in completed.stderr and len(completed.stderr.strip().splitlines()) == 1


def test_a_fault_from_the_command_line_reaches_the_scenario_the_simulator_loads(tmp_path):
    from coopdrive.cli import _extra_faults, build_parser

    args = build_parser().parse_args(["run", str(EXAMPLE), "--fault",
                                      "{type: gnss_jump, vehicle_id: ego, start_s: 3, end_s: 3.5, east_m: 5}"])
    scenario = load_scenario(sim_config(tmp_path, extra_faults=_extra_faults(args))["scenario_file"])
    assert [(f.start_s, f.end_s, f.east_m) for f in scenario.faults if f.type == "gnss_jump"] == [(3.0, 3.5, 5.0)]
