"""Text export of a machine's graph: Mermaid (HMI, docs) and Graphviz DOT."""

from __future__ import annotations

from .engine import EngineEvent, MachineSpec


def _label(text: str) -> str:
    return text.replace('"', "'")


def _edges(spec: MachineSpec) -> list[tuple[str, str, str]]:
    edges: list[tuple[str, str, str]] = []
    for t in spec.transitions:
        guard = f" if {t.guard.__name__}" if t.guard is not None else ""
        edges.append((t.source.name, t.target.name, t.event.name + guard))
    for s in spec.states:
        if s.escape is not None:
            edges.append((s.state.name, s.escape.name, f"{EngineEvent.TIMEOUT.name} {s.timeout_s:g} s"))
    seen: set[tuple[str, str, str]] = set()
    unique = []
    for edge in edges:
        if edge not in seen:
            seen.add(edge)
            unique.append(edge)
    return unique


def to_mermaid(spec: MachineSpec) -> str:
    """A Mermaid stateDiagram-v2; safe states are noted, terminal states lead to [*]."""
    lines = ["stateDiagram-v2", f"    %% machine {spec.name}", f"    [*] --> {spec.initial.name}"]
    for s in spec.states:
        lines.append(f"    state \"{_label(s.state.name)}\" as {s.state.name}")
    for source, target, label in _edges(spec):
        lines.append(f"    {source} --> {target}: {_label(label)}")
    for s in spec.states:
        if s.terminal:
            lines.append(f"    {s.state.name} --> [*]")
    for s in spec.states:
        if s.safe:
            lines.append(f"    note right of {s.state.name} : safe")
    return "\n".join(lines) + "\n"


def to_dot(spec: MachineSpec) -> str:
    """A Graphviz digraph; waiting states dashed, safe states green, terminal states doubled."""
    lines = [f"digraph \"{spec.name}\" {{", "    rankdir=LR;", "    __start [shape=point];",
             f"    __start -> \"{spec.initial.name}\";"]
    for s in spec.states:
        attrs = ["shape=doublecircle" if s.terminal else "shape=box"]
        if s.waiting:
            attrs.append("style=dashed")
        if s.safe:
            attrs.append("color=green")
        lines.append(f"    \"{s.state.name}\" [{', '.join(attrs)}];")
    for source, target, label in _edges(spec):
        lines.append(f"    \"{source}\" -> \"{target}\" [label=\"{_label(label)}\"];")
    lines.append("}")
    return "\n".join(lines) + "\n"
