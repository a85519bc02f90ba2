"""`coopdrive group SPEC.json`: a vehicle's services in one process; a bad spec stops it with one line."""

import json
import subprocess
import sys


def run_group(spec_path, endpoint):
    return subprocess.run([sys.executable, "-m", "coopdrive.cli", "group", str(spec_path), "--connect", endpoint],
                          capture_output=True, text=True, timeout=60)


def test_an_unknown_service_in_the_spec_is_named_in_one_line(tmp_path, endpoint):
    spec = tmp_path / "group.json"
    spec.write_text(json.dumps([{"service": "control", "vehicle": "v1"}, {"service": "teleport", "vehicle": "v1"}]))
    result = run_group(spec, endpoint)
    assert result.returncode == 2
    assert "teleport" in result.stderr and len(result.stderr.strip().splitlines()) == 1


def test_a_bad_config_key_names_the_entry_and_the_key(tmp_path, endpoint):
    spec = tmp_path / "group.json"
    spec.write_text(json.dumps([{"service": "control", "vehicle": "v1", "config": {"period_s": -1}}]))
    result = run_group(spec, endpoint)
    assert result.returncode == 2
    assert "[0]" in result.stderr and "period_s" in result.stderr


def test_a_spec_that_is_not_json_is_refused(tmp_path, endpoint):
    spec = tmp_path / "group.json"
    spec.write_text("[{")
    result = run_group(spec, endpoint)
    assert result.returncode == 2 and "group.json" in result.stderr
