"""The system commands some tests use, from tools/system-packages.tsv: a test asks for one with `require`, which
skips naming the Debian package and the script that installs it. Under CI such a skip fails the test instead
(tests/conftest.py), so CI always runs them all."""

import shutil
from pathlib import Path

import pytest

TABLE = Path(__file__).resolve().parents[1] / "tools" / "system-packages.tsv"
# The start of every skip reason `require` gives; tests/conftest.py turns such a skip into a failure under CI.
MISSING = "system package missing:"


def packages() -> dict[str, str]:
    """Command -> the Debian package that brings it."""
    rows = [line.split("\t") for line in TABLE.read_text(encoding="utf-8").splitlines()
            if line.strip() and not line.startswith("#")]
    return {row[0]: row[1] for row in rows}


def _skip_reason(command: str) -> str:
    return f"{MISSING} {packages()[command]} (no `{command}` on PATH; install it with tools/system_packages.sh)"


def require(command: str) -> str:
    """The command's path; skips when it is missing (the command must be in tools/system-packages.tsv)."""
    path = shutil.which(command)
    if path is None:
        pytest.skip(_skip_reason(command))
    return path


def needs(command: str) -> pytest.MarkDecorator:
    """A mark that skips a test, or a module as `pytestmark`, while the command is missing."""
    return pytest.mark.skipif(shutil.which(command) is None, reason=_skip_reason(command))


def fail_if_ci_skipped_for_a_package(report, environment) -> None:
    """Under CI (CI=true) a report skipped for a missing system package becomes a failure: `.ci/run` installs them
    all first, so such a skip means a package went missing from tools/system-packages.tsv or its install."""
    if not (report.skipped and environment.get("CI") == "true" and isinstance(report.longrepr, tuple)):
        return
    reason = report.longrepr[2].removeprefix("Skipped: ")
    if reason.startswith(MISSING):
        report.outcome = "failed"
        report.longrepr = f"CI runs every test: {reason}"
