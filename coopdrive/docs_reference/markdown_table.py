"""Markdown tables whose cells may hold any text: a pipe would end a cell and a line break the row."""

from __future__ import annotations

from typing import Iterable, Sequence


def one_line(text: object) -> str:
    return " ".join(str(text).split())


def cell(text: object) -> str:
    """Plain text in a cell, its pipes escaped."""
    return one_line(text).replace("|", "\\|")


def code(text: object) -> str:
    """Inline code in a cell (Python-Markdown's tables leave a pipe inside a code span alone); empty stays empty."""
    value = one_line(text).replace("`", "'")
    return f"`{value}`" if value else ""


def table(header: Sequence[str], rows: Iterable[Sequence[str]]) -> str:
    """Rows of cells already made with cell() or code()."""
    lines = ["| " + " | ".join(header) + " |", "|" + "---|" * len(header)]
    lines += ["| " + " | ".join(row) + " |" for row in rows]
    return "\n".join(lines)
