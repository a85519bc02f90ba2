"""Config files and overrides: every error names the file and the key."""

import subprocess
import sys

import pytest

from coopdrive.runtime.config import ConfigError, load_config
from coopdrive.services.control.service import ControlService


def test_overrides_keep_their_types(tmp_path):
    path = tmp_path / "planner.yaml"
    path.write_text("rate_hz: 5\n")
    from coopdrive.services.planner.service import PlannerService

    config = load_config(PlannerService.Config, path, ["station_id=7"])
    assert config.rate_hz == 5 and config.station_id == 7


def test_an_unknown_key_is_named_with_the_file(tmp_path):
    path = tmp_path / "planner.yaml"
    path.write_text("rate_hz: 5\nspeeed: 3\n")
    from coopdrive.services.planner.service import PlannerService

    with pytest.raises(ConfigError, match=r"planner.yaml: speeed: Extra inputs are not permitted"):
        load_config(PlannerService.Config, path)


def test_a_value_of_the_wrong_type_is_named(tmp_path):
    path = tmp_path / "planner.yaml"
    path.write_text("rate_hz: fast\n")
    from coopdrive.services.planner.service import PlannerService

    with pytest.raises(ConfigError, match=r"rate_hz: Input should be a valid number"):
        load_config(PlannerService.Config, path)


def test_a_file_that_is_not_yaml_is_reported(tmp_path):
    path = tmp_path / "broken.yaml"
    path.write_text("rate_hz: [1, 2\n")
    with pytest.raises(ConfigError, match="broken.yaml: not valid YAML"):
        load_config(ControlService.Config, path)


def test_the_service_command_refuses_a_bad_key_with_one_line_and_starts_nothing():
    result = subprocess.run([sys.executable, "-m", "coopdrive.cli", "service", "planner", "--set", "no_such_key=1"],
                            capture_output=True, text=True, timeout=60)
    assert result.returncode == 2
    assert result.stderr.strip().splitlines() == ["coopdrive: --set: no_such_key: Extra inputs are not permitted"]


def test_an_unknown_service_name_is_refused():
    result = subprocess.run([sys.executable, "-m", "coopdrive.cli", "service", "teleporter"],
                            capture_output=True, text=True, timeout=60)
    assert result.returncode == 2
    assert "unknown service 'teleporter'" in result.stderr
