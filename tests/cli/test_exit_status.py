"""Every command's exit statuses are said once, in coopdrive/exit_status.py: no other module of the framework or
the services gives an EXIT_ name a value of its own."""

import ast
from pathlib import Path

ROOT = Path(__file__).parents[2]
HOME = ROOT / "coopdrive" / "exit_status.py"


def exit_status_assignments(source: str) -> list[str]:
    names = []
    for node in ast.walk(ast.parse(source)):
        targets = node.targets if isinstance(node, ast.Assign) else [node.target] if isinstance(
            node, (ast.AnnAssign, ast.AugAssign)) else []
        for target in targets:
            for name in ast.walk(target):
                if isinstance(name, ast.Name) and name.id.startswith("EXIT_"):
                    names.append(name.id)
    return names


def test_no_module_but_exit_status_py_assigns_an_exit_status():
    found = [f"{path.relative_to(ROOT)}: {name}" for folder in ("coopdrive", "services")
             for path in sorted((ROOT / folder).rglob("*.py")) if path != HOME
             for name in exit_status_assignments(path.read_text(encoding="utf-8"))]
    assert found == []


def test_the_check_finds_statuses_assigned_one_by_one_and_as_a_tuple():
    assert exit_status_assignments("EXIT_OK, EXIT_USAGE = 0, 2\nEXIT_FAILED: int = 1\nOTHER = 3\n") == [
        "EXIT_OK", "EXIT_USAGE", "EXIT_FAILED"]
    assert exit_status_assignments(HOME.read_text()) == ["EXIT_OK", "EXIT_FAILED", "EXIT_USAGE", "EXIT_ORPHANED",
                                                               "EXIT_INCOMPLETE"]
