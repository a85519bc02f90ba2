"""docs/architecture.md's generated part is what the services table and the topic declarations say today."""

from pathlib import Path

import pytest

from coopdrive.bus import architecture

PAGE = Path(__file__).resolve().parents[2] / "docs" / "architecture.md"


def test_the_committed_page_shows_the_services_and_topics_of_the_code():
    committed = architecture.committed_section(PAGE.read_text(encoding="utf-8"))
    assert committed == architecture.generated_section(), (
        "docs/architecture.md is stale: run python -m coopdrive.bus.architecture --write docs/architecture.md")


def test_rewriting_replaces_only_the_generated_part():
    page = f"before\n{architecture.BEGIN}\nold\n{architecture.END}\nafter\n"
    assert architecture.rewrite(page, "new\n") == "before\nnew\nafter\n"
    with pytest.raises(ValueError, match="no generated part"):
        architecture.rewrite("no markers\n", "new\n")


def test_the_picture_draws_each_reader_of_a_topic_once():
    edges = [line for line in architecture.mermaid() if "-->" in line]
    assert '    control -->|"control/command"| actuation' in edges
    assert len(edges) == len(set(edges))
    assert not any("v2x -->" in line and line.endswith("| v2x") for line in edges)
