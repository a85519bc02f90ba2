"""The framework sits below the applications, and no two modules import each other, read from the import graph of
the installed package (tests/import_graph.py: every module, relative and deferred imports too).

- Every module belongs to one of the layers of coopdrive/bus/layers.py, and a layer never reaches a higher one,
  directly or through any chain of imports: no framework module reaches a service or an application (the
  launcher, the judge, the command line), since a service class is named in the services table and imported only
  when it is started.
- No service reaches another service.
- No import cycle anywhere: a module never ends up importing itself.

The one thing the framework reads of a service is its topic declaration (services/<name>/topics.py, named in the
services table as a string and imported by the topic registry on first use). That is not an import of service code
only while a declaration imports nothing but the Topic type and protobuf messages, which the last test holds."""

import importlib.util
from pathlib import Path

import pytest

from coopdrive.bus.layers import LAYERS, ROOT_PACKAGE, layer_of
from coopdrive.bus.services import SERVICES
from import_graph import ROOT, cycles, import_graph, imported_names, path_to, reach

FRAMEWORK_LAYERS = [layer for layer in LAYERS if layer.framework]
FRAMEWORK = tuple(package for layer in FRAMEWORK_LAYERS for package in layer.packages)
ABOVE = tuple(package for layer in LAYERS if not layer.framework for package in layer.packages)

@pytest.fixture(scope="module")
def graph():
    return import_graph()


def in_package(module: str, packages) -> bool:
    return any(module == package or module.startswith(package + ".") for package in packages)


def reaches(graph, modules, forbidden) -> list[str]:
    """`module -> ... -> forbidden module` for each of `modules` that reaches one (the first found)."""
    found = []
    for module in sorted(modules):
        reached = reach(graph, module)
        bad = sorted(target for target in reached if in_package(target, forbidden))
        if bad:
            found.append(" -> ".join(path_to(reached, module, bad[0])))
    return found


def test_the_graph_holds_every_module_of_the_framework_and_the_services(graph):
    assert {"coopdrive.bus.session", "coopdrive.v2x.packet", "coopdrive.services.v2x.service",
            "coopdrive.services.sim.service", "coopdrive.cli"} <= set(graph)
    assert "coopdrive.v2x.packet" in graph["coopdrive.services.v2x.transmission"]


@pytest.mark.parametrize("package", FRAMEWORK)
def test_no_framework_module_reaches_a_service_or_an_application(graph, package):
    assert reaches(graph, [module for module in graph if in_package(module, [package])], ABOVE) == []


def test_every_module_belongs_to_a_layer(graph):
    assert [module for module in graph if module != ROOT_PACKAGE and layer_of(module) is None] == []


@pytest.mark.parametrize("level", range(len(LAYERS) - 1), ids=lambda level: LAYERS[level].name)
def test_no_layer_reaches_a_higher_one(graph, level):
    higher = [package for layer in LAYERS[level + 1:] for package in layer.packages]
    assert reaches(graph, [module for module in graph if in_package(module, LAYERS[level].packages)], higher) == []


@pytest.mark.parametrize("entry", SERVICES, ids=lambda entry: entry.name)
def test_no_service_reaches_another_service(graph, entry):
    """What two services share is a topic's message or a library below them (the V2X library for the simulator and
    the v2x service), never one's code in the other."""
    own = f"coopdrive.services.{entry.name}"
    others = [f"coopdrive.services.{other.name}" for other in SERVICES if other.name != entry.name]
    assert reaches(graph, [module for module in graph if in_package(module, [own])], others) == []


def test_no_two_modules_import_each_other_in_a_cycle_anywhere(graph):
    assert cycles(graph) == []


def test_no_framework_module_is_part_of_a_cycle_even_an_allowed_one(graph):
    assert [cycle for cycle in cycles(graph) if any(in_package(module, FRAMEWORK) for module in cycle)] == []


# The checks themselves, on made-up sources and on the real graph with one import added.
INJECTED_CYCLE = {
    "coopdrive.bus.__init__": "",
    "coopdrive.bus.a": "def later():\n    from . import b\n",
    "coopdrive.bus.b": "import coopdrive.bus.c\n",
    "coopdrive.bus.c": "from coopdrive.bus.a import later\n",
}


def test_the_cycle_check_finds_a_cycle_through_a_deferred_and_a_relative_import():
    sources = {name.removesuffix(".__init__"): source for name, source in INJECTED_CYCLE.items()}
    assert cycles(import_graph(sources=sources)) == [["coopdrive.bus.a", "coopdrive.bus.b", "coopdrive.bus.c"]]


def test_the_cycle_check_finds_a_cycle_added_to_the_real_graph(graph):
    injected = {module: set(targets) for module, targets in graph.items()}
    injected["coopdrive.geodesy.origin"].add("coopdrive.roadmap")
    assert any("coopdrive.geodesy.origin" in cycle for cycle in cycles(injected))


def test_the_reach_check_finds_a_service_reached_through_another_framework_module(graph):
    injected = {module: set(targets) for module, targets in graph.items()}
    injected["coopdrive.messages.unknowns"].add("coopdrive.services.scene.service")
    found = reaches(injected, ["coopdrive.bus.session"], ABOVE) + reaches(injected, ["coopdrive.visual"], ABOVE)
    assert found and all("coopdrive.messages.unknowns -> coopdrive.services.scene.service" in line for line in found)


def test_imports_resolve_relative_names_and_name_modules_imported_from_a_package():
    source = "from .b import c\nfrom .. import d\nimport e.f\n"
    assert imported_names(source, "p.q.a", is_package=False) == {"p.q.b", "p.q.b.c", "p", "p.d", "e.f"}


def test_an_import_under_type_checking_is_no_import():
    source = "from typing import TYPE_CHECKING\nif TYPE_CHECKING:\n    import p.b\nelse:\n    import p.c\n"
    assert imported_names(source, "p.a", is_package=False) == {"typing", "typing.TYPE_CHECKING", "p.c"}


# What a topic declaration may import: reading one must not start any of its service's code.
DECLARATION_IMPORTS = ("coopdrive.bus.topic", "coopdrive.v1")


@pytest.mark.parametrize("entry", SERVICES, ids=lambda entry: entry.name)
def test_a_topic_declaration_imports_only_the_topic_type_and_messages(entry):
    path = Path(importlib.util.find_spec(entry.declarations).origin)
    imported = imported_names(path.read_text(encoding="utf-8"), entry.declarations, is_package=False)
    offending = [name for name in imported if not in_package(name, DECLARATION_IMPORTS)
                 and not name.startswith("coopdrive.bus.topic.")]
    assert path.is_relative_to(ROOT) and offending == []
