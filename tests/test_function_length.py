"""No function over MAX_FUNCTION_LINES lines in the framework or the services (generated protobuf code aside): a
longer one is doing several things a reader would rather find by name."""

import ast
from pathlib import Path

import pytest

ROOT = Path(__file__).parents[1]
MAX_FUNCTION_LINES = 60
CHECKED = ("coopdrive", "services")


def long_functions(source: str, file_name: str, limit: int = MAX_FUNCTION_LINES) -> list[str]:
    return [f"{file_name}:{node.lineno} {node.name} ({node.end_lineno - node.lineno + 1} lines)"
            for node in ast.walk(ast.parse(source)) if isinstance(node, (ast.FunctionDef, ast.AsyncFunctionDef))
            and node.end_lineno - node.lineno + 1 > limit]


@pytest.mark.parametrize("folder", CHECKED)
def test_no_function_is_longer_than_sixty_lines(folder):
    paths = [path for path in sorted((ROOT / folder).rglob("*.py")) if not path.name.endswith("_pb2.py")]
    assert paths
    found = [line for path in paths
             for line in long_functions(path.read_text(encoding="utf-8"), str(path.relative_to(ROOT)))]
    assert found == []


def test_the_check_finds_a_function_one_line_too_long_and_passes_one_at_the_limit():
    body = "".join(f"    x{k} = {k}\n" for k in range(MAX_FUNCTION_LINES))
    assert long_functions(f"def too_long():\n{body}", "example.py") == ["example.py:1 too_long (61 lines)"]
    at_limit = body.split("\n", 1)[1]
    assert long_functions(f"def at_the_limit():\n{at_limit}", "example.py") == []
