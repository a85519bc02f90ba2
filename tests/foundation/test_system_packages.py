"""System packages are installed once before the suite (tools/system_packages.sh), never by a test; a test that
needs one skips naming it, and under CI such a skip fails."""

import os
import shutil
import subprocess
from pathlib import Path

import pytest

from tests.system_packages import MISSING, TABLE, packages

REPO = Path(__file__).resolve().parents[2]
SCRIPT = REPO / "tools" / "system_packages.sh"
pytest_plugins = ["pytester"]

SKIPPING_TEST = f"""
import pytest

def test_needs_a_browser():
    pytest.skip("{MISSING} chromium (no `chromium` on PATH)")

def test_skips_for_another_reason():
    pytest.skip("this kernel has no autogroups")
"""


@pytest.fixture
def suite(pytester):
    pytester.makeconftest("from tests.conftest import pytest_runtest_makereport")
    pytester.makepyfile(SKIPPING_TEST)
    return pytester


def test_under_ci_a_skip_for_a_missing_system_package_fails_and_other_skips_stay_skips(suite, monkeypatch):
    monkeypatch.setenv("CI", "true")
    result = suite.runpytest_inprocess("-p", "no:randomly")
    result.assert_outcomes(failed=1, skipped=1)
    result.stdout.fnmatch_lines(["*CI runs every test: system package missing: chromium*"])


def test_outside_ci_a_skip_for_a_missing_system_package_stays_a_skip(suite, monkeypatch):
    monkeypatch.delenv("CI", raising=False)
    suite.runpytest_inprocess().assert_outcomes(skipped=2)


def test_no_test_installs_a_package_itself():
    installing = [str(path.relative_to(REPO)) for path in (REPO / "tests").rglob("*.py")
                  if "apt-get" in path.read_text(encoding="utf-8") and path != Path(__file__)]
    assert installing == []


def test_the_table_names_each_command_the_tests_ask_for():
    assert {"tshark", "chromium", "docker-compose", "valgrind"} <= set(packages())


def a_machine_without(tmp_path: Path, command: str, root: bool) -> tuple[Path, dict]:
    """The script and a table of one missing command, with an `id` that says root or not."""
    (tmp_path / "tools").mkdir()
    script = tmp_path / "tools" / SCRIPT.name
    shutil.copy(SCRIPT, script)
    (tmp_path / "tools" / TABLE.name).write_text(f"# command\tpackage\ttests\n{command}\t{command}-pkg\tthe x tests\n")
    bin_dir = tmp_path / "bin"
    bin_dir.mkdir()
    (bin_dir / "id").write_text(f"#!/bin/sh\necho {0 if root else 1000}\n")
    (bin_dir / "id").chmod(0o755)
    (bin_dir / "apt-get").write_text("#!/bin/sh\necho apt-get \"$@\" >> \"$APT_LOG\"\n")
    (bin_dir / "apt-get").chmod(0o755)
    return script, {**os.environ, "PATH": f"{bin_dir}:/usr/bin:/bin", "APT_LOG": str(tmp_path / "apt.log")}


def test_without_root_the_script_names_the_missing_package_and_the_tests_that_will_skip(tmp_path):
    script, environment = a_machine_without(tmp_path, "no-such-command", root=False)
    result = subprocess.run(["bash", str(script)], env=environment, capture_output=True, text=True, timeout=60)
    assert result.returncode == 0
    assert "no-such-command-pkg is missing, so these tests will skip: the x tests" in result.stdout
    strict = subprocess.run(["bash", str(script), "--require"], env=environment, capture_output=True, text=True,
                            timeout=60)
    assert strict.returncode == 1


def test_as_root_the_script_installs_the_missing_package_with_apt(tmp_path):
    script, environment = a_machine_without(tmp_path, "no-such-command", root=True)
    result = subprocess.run(["bash", str(script)], env=environment, capture_output=True, text=True, timeout=60)
    assert result.returncode == 0, result.stderr
    log = (tmp_path / "apt.log").read_text().splitlines()
    assert any(line.endswith("update -qq") for line in log)
    assert any("install" in line and line.endswith("no-such-command-pkg") for line in log)
