"""The suite's own order: files that start whole scenario runs are marked and handed to the workers first."""

import re
from pathlib import Path
from types import SimpleNamespace

from tests.conftest import WHOLE_RUN, pytest_collection_modifyitems

TESTS = Path(__file__).resolve().parent
# A run started as a user starts it (`python -m coopdrive.cli run ...`, `cli.main(["run", ...])`), or through the
# helpers that do so.
STARTS_A_RUN = re.compile(r'"coopdrive\.cli", "run"|main\(\["run"|run_scenario_report\(|start_follow_run\(')
MARKED = "pytestmark = pytest.mark.whole_run"
HELPERS = {TESTS / "scenario_report.py", TESTS / "gateway" / "conftest.py"}


def item(file: str, name: str, whole_run: bool) -> SimpleNamespace:
    return SimpleNamespace(nodeid=f"{file}::{name}",
                           get_closest_marker=lambda marker: marker if whole_run and marker == WHOLE_RUN else None)


def test_the_files_that_start_whole_runs_come_first_each_file_together_and_in_its_own_order():
    items = [item("a.py", "one", False), item("a.py", "two", False), item("b.py", "one", True),
             item("b.py", "two", True), item("c.py", "one", False), item("d.py", "one", True)]
    pytest_collection_modifyitems(items)
    assert [i.nodeid for i in items] == ["b.py::one", "b.py::two", "d.py::one", "a.py::one", "a.py::two",
                                         "c.py::one"]


def test_every_test_file_that_starts_a_scenario_run_is_marked_whole_run():
    unmarked = [str(path.relative_to(TESTS)) for path in sorted(TESTS.rglob("test_*.py"))
                if path not in HELPERS and STARTS_A_RUN.search(path.read_text()) and MARKED not in path.read_text()]
    assert not unmarked, f"these start whole runs: add `{MARKED}` so that they are run first: {unmarked}"
