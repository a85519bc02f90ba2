"""The framework sits below the applications: bus, runtime, recording, CAN, geodesy and road map code never
imports a service, the simulator, the launcher, the judge or the command line (a service class is named in the
services table and imported only when it is started).

The one thing the framework reads of a service is its topic declaration (services/<name>/topics.py, named in the
services table as a string and imported by the topic registry on first use). That is not an import of service code
only while a declaration imports nothing but the Topic type and protobuf messages, which the last test holds."""

import ast
import importlib.util
from pathlib import Path

import pytest

import coopdrive
from coopdrive.bus.services import SERVICES

FRAMEWORK = ("bus", "runtime", "recording", "can", "geodesy", "roadmap")
ABOVE = ("coopdrive.services", "coopdrive.launch", "coopdrive.judging", "coopdrive.analysis", "coopdrive.cli")
PACKAGE_DIR = Path(coopdrive.__file__).parent


def imported_modules(path: Path) -> list[str]:
    names = []
    for node in ast.walk(ast.parse(path.read_text(encoding="utf-8"))):
        if isinstance(node, ast.Import):
            names += [alias.name for alias in node.names]
        elif isinstance(node, ast.ImportFrom) and node.module and node.level == 0:
            names.append(node.module)
    return names


@pytest.mark.parametrize("layer", FRAMEWORK)
def test_no_framework_module_imports_a_service_or_an_application(layer):
    offending = [f"{path.relative_to(PACKAGE_DIR.parent)}: {name}"
                 for path in sorted((PACKAGE_DIR / layer).rglob("*.py"))
                 for name in imported_modules(path) if name.startswith(ABOVE)]
    assert offending == []


def test_the_check_sees_an_offending_import():
    source = PACKAGE_DIR / "runtime" / "registry.py"
    assert all(not name.startswith(ABOVE) for name in imported_modules(source))
    assert any(name.startswith(ABOVE) for name in imported_modules(PACKAGE_DIR / "launch" / "run.py"))


# What a topic declaration may import: reading one must not start any of its service's code.
DECLARATION_IMPORTS = ("coopdrive.bus.topic", "coopdrive.v1")


@pytest.mark.parametrize("entry", SERVICES, ids=lambda entry: entry.name)
def test_a_topic_declaration_imports_only_the_topic_type_and_messages(entry):
    path = Path(importlib.util.find_spec(entry.declarations).origin)
    offending = [name for name in imported_modules(path)
                 if name not in DECLARATION_IMPORTS and not name.startswith("coopdrive.v1.")]
    assert offending == []
