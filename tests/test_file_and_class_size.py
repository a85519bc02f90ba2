"""No file over MAX_FILE_LINES lines and no class over MAX_CLASS_LINES lines in the framework, the services, the
benchmarks and the tests (generated protobuf code aside): a longer one holds several roles a reader would rather
find each in a file of its own."""

import ast
from pathlib import Path

import pytest

ROOT = Path(__file__).parents[1]
MAX_FILE_LINES = 400
MAX_CLASS_LINES = 300
CHECKED = ("coopdrive", "services", "bench", "tests")



def sources(folder: str) -> list[Path]:
    return [path for path in sorted((ROOT / folder).rglob("*.py")) if not path.name.endswith("_pb2.py")]


def long_file(source: str, file_name: str, limit: int = MAX_FILE_LINES) -> list[str]:
    lines = len(source.splitlines())
    return [f"{file_name} ({lines} lines)"] if lines > limit else []


def long_classes(source: str, file_name: str, limit: int = MAX_CLASS_LINES) -> list[str]:
    return [f"{file_name}:{node.lineno} {node.name} ({node.end_lineno - node.lineno + 1} lines)"
            for node in ast.walk(ast.parse(source)) if isinstance(node, ast.ClassDef)
            and node.end_lineno - node.lineno + 1 > limit]


@pytest.mark.parametrize("folder", CHECKED)
def test_no_file_is_longer_than_four_hundred_lines(folder):
    paths = sources(folder)
    assert paths
    found = [line for path in paths
             for line in long_file(path.read_text(encoding="utf-8"), str(path.relative_to(ROOT)))]
    assert found == []


@pytest.mark.parametrize("folder", CHECKED)
def test_no_class_is_longer_than_three_hundred_lines(folder):
    found = [line for path in sources(folder)
             for line in long_classes(path.read_text(encoding="utf-8"), str(path.relative_to(ROOT)))]
    assert found == []


def test_the_checks_find_a_file_and_a_class_one_line_too_long_and_pass_them_at_the_limit():
    at_file_limit = "x = 0\n" * MAX_FILE_LINES
    assert long_file(at_file_limit, "example.py") == []
    assert long_file(at_file_limit + "y = 1\n", "example.py") == [f"example.py ({MAX_FILE_LINES + 1} lines)"]
    body = "".join(f"    x{k} = {k}\n" for k in range(MAX_CLASS_LINES))
    assert long_classes(f"class TooLong:\n{body}", "example.py") == [
        f"example.py:1 TooLong ({MAX_CLASS_LINES + 1} lines)"]
    assert long_classes(f"class AtTheLimit:\n{body.split(chr(10), 1)[1]}", "example.py") == []
