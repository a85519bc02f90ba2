"""The import graph of the installed package, read from the source: every module under coopdrive/ and services/
(installed as coopdrive.services) and the coopdrive modules each one imports, wherever the import statement stands
(a deferred import inside a function is an import too). Imports under `if TYPE_CHECKING:` are left out: they never
run. Used by tests/test_import_direction.py."""

from __future__ import annotations

import ast
from collections.abc import Iterable, Mapping
from pathlib import Path

ROOT = Path(__file__).parents[1]
# Source folder -> the package it is installed as (setup.py's package_dir).
PACKAGE_FOLDERS = {"coopdrive": "coopdrive", "services": "coopdrive.services"}

Graph = Mapping[str, set[str]]


def module_files(root: Path = ROOT) -> dict[str, Path]:
    """Module name -> its file, generated protobuf modules aside."""
    modules = {}
    for folder, package in PACKAGE_FOLDERS.items():
        for path in sorted((root / folder).rglob("*.py")):
            if path.name.endswith("_pb2.py"):
                continue
            parts = list(path.relative_to(root / folder).with_suffix("").parts)
            if parts[-1] == "__init__":
                parts = parts[:-1]
            modules[".".join([package, *parts])] = path
    # services/ lies inside no coopdrive folder, so its modules would otherwise be named twice.
    return {name: path for name, path in modules.items() if not name.startswith("coopdrive.services.services")}


def _is_type_checking(node: ast.If) -> bool:
    test = node.test
    return (isinstance(test, ast.Name) and test.id == "TYPE_CHECKING") or \
        (isinstance(test, ast.Attribute) and test.attr == "TYPE_CHECKING")


def _statements(tree: ast.AST) -> Iterable[ast.AST]:
    """Every node of the tree but what stands under `if TYPE_CHECKING:`."""
    stack = [tree]
    while stack:
        node = stack.pop()
        yield node
        if isinstance(node, ast.If) and _is_type_checking(node):
            stack.extend(node.orelse)
            continue
        stack.extend(ast.iter_child_nodes(node))


def imported_names(source: str, module: str, is_package: bool) -> set[str]:
    """The dotted names `module`'s source imports, relative imports resolved; `from P import N` gives P.N too (N may be
    a module of P)."""
    package = module if is_package else module.rpartition(".")[0]
    names = set()
    for node in _statements(ast.parse(source)):
        if isinstance(node, ast.Import):
            names.update(alias.name for alias in node.names)
        elif isinstance(node, ast.ImportFrom):
            base = package.split(".")
            if node.level:
                base = base[:len(base) - node.level + 1]
                target = ".".join(base + ([node.module] if node.module else []))
            else:
                target = node.module
            names.add(target)
            names.update(f"{target}.{alias.name}" for alias in node.names)
    return names


def import_graph(modules: Mapping[str, Path] | None = None, sources: Mapping[str, str] | None = None) -> dict[str, set[str]]:
    """Module -> the package's modules it imports. `sources` (module -> source) stands in for reading `modules`."""
    if sources is None:
        modules = module_files() if modules is None else modules
        sources = {name: path.read_text(encoding="utf-8") for name, path in modules.items()}
        packages = {name for name, path in modules.items() if path.name == "__init__.py"}
    else:
        packages = {name.rpartition(".")[0] for name in sources if "." in name}
    return {name: {target for target in imported_names(source, name, name in packages)
                   if target in sources and target != name}
            for name, source in sources.items()}


def reach(graph: Graph, start: str) -> dict[str, str]:
    """Every module `start` imports directly or transitively -> the module that imports it on one shortest path."""
    found: dict[str, str] = {}
    frontier = [start]
    while frontier:
        following = []
        for module in frontier:
            for target in sorted(graph.get(module, ())):
                if target not in found and target != start:
                    found[target] = module
                    following.append(target)
        frontier = following
    return found


def path_to(found: Mapping[str, str], start: str, target: str) -> list[str]:
    path = [target]
    while path[-1] != start:
        path.append(found[path[-1]])
    return path[::-1]


def cycles(graph: Graph) -> list[list[str]]:
    """The strongly connected components of more than one module (Tarjan's algorithm, iterative), each sorted."""
    index: dict[str, int] = {}
    low: dict[str, int] = {}
    on_stack: set[str] = set()
    stack: list[str] = []
    components = []
    for root in sorted(graph):
        if root in index:
            continue
        work = [(root, iter(sorted(graph[root])))]
        index[root] = low[root] = len(index)
        stack.append(root)
        on_stack.add(root)
        while work:
            node, targets = work[-1]
            target = next(targets, None)
            if target is not None:
                if target not in index:
                    index[target] = low[target] = len(index)
                    stack.append(target)
                    on_stack.add(target)
                    work.append((target, iter(sorted(graph.get(target, ())))))
                elif target in on_stack:
                    low[node] = min(low[node], index[target])
                continue
            work.pop()
            if work:
                low[work[-1][0]] = min(low[work[-1][0]], low[node])
            if low[node] == index[node]:
                component = []
                while True:
                    member = stack.pop()
                    on_stack.discard(member)
                    component.append(member)
                    if member == node:
                        break
                if len(component) > 1:
                    components.append(sorted(component))
    return sorted(components)
