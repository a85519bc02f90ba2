"""`coopdrive run --set SERVICE.KEY=VALUE`: a config key of a service in every stack (or of the simulator), checked
against that service's config before anything starts, and carried into each stack's service config."""

import subprocess
import sys

import pytest

from coopdrive.cli import service_settings
from coopdrive.launch.run import RunOptions, build_specs
from coopdrive.runtime.config import ConfigError

# It starts `coopdrive run`, if only to see it refuse a setting before the run begins.
pytestmark = pytest.mark.whole_run


def test_settings_are_grouped_by_service_with_their_values_typed():
    assert service_settings(["planner.glosa=false", "geolocation.geolocator.gnss_error_std_m=0.3",
                             "planner.logic.signals.spat_stale_s=2"]) == {
        "planner": {"glosa": False, "logic": {"signals": {"spat_stale_s": 2}}},
        "geolocation": {"geolocator": {"gnss_error_std_m": 0.3}}}


@pytest.mark.parametrize("assignment, said", [
    ("planer.glosa=false", "expected SERVICE.KEY=VALUE, SERVICE one of sim, geolocation"),
    ("planner=false", "expected SERVICE.KEY=VALUE"),
    ("control.no_such_key=3", "--set control: no_such_key: Extra inputs are not permitted"),
    ("planner.glosa=maybe", "--set planner: glosa: Input should be a valid boolean"),
])
def test_a_setting_of_no_service_or_no_key_or_a_wrong_value_is_refused_naming_it(assignment, said):
    with pytest.raises(ConfigError) as raised:
        service_settings([assignment])
    assert said in str(raised.value)


def test_each_stack_s_planner_gets_the_setting(tmp_path):
    options = RunOptions(scenario="signals", stacks=2, service_overrides=service_settings(["planner.glosa=false"]))
    planners = [spec for spec in build_specs(options, tmp_path) if spec.service == "planner"]
    assert len(planners) == 2 and all(spec.config["glosa"] is False for spec in planners)


def test_the_command_refuses_a_bad_setting_in_one_line_and_starts_nothing():
    completed = subprocess.run([sys.executable, "-m", "coopdrive.cli", "run", "signals", "--set", "planner.glosa=maybe"],
                               capture_output=True, text=True, timeout=60)
    assert completed.returncode == 2
    assert len(completed.stderr.strip().splitlines()) == 1 and "--set planner: glosa" in completed.stderr
