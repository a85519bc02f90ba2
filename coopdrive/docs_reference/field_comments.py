"""What a pydantic model's source says of each field: its `Field(description=...)`, else the comment lines right
above the field and the comment at the end of its line. The config models document their keys in comments (the
house style), so the reference reads them from there rather than asking every model to repeat itself."""

from __future__ import annotations

import ast
import inspect
import io
import textwrap
import tokenize
from functools import lru_cache


@lru_cache(maxsize=None)
def class_comments(cls: type) -> dict[str, str]:
    """Field name -> its comment, for the fields declared in this class itself (not its bases)."""
    try:
        source = textwrap.dedent(inspect.getsource(cls))
    except (OSError, TypeError):
        return {}
    comments = _comments_by_line(source)
    lines = source.splitlines()
    found: dict[str, str] = {}
    class_node = ast.parse(source).body[0]
    for node in getattr(class_node, "body", []):
        if isinstance(node, ast.AnnAssign) and isinstance(node.target, ast.Name):
            above = _block_above(node.lineno, lines, comments)
            inline = [comments[n] for n in range(node.lineno, (node.end_lineno or node.lineno) + 1)
                      if n in comments and not _is_comment_line(lines[n - 1])]
            text = " ".join(above + inline).strip()
            if text:
                found[node.target.id] = text
    return found


def _comments_by_line(source: str) -> dict[int, str]:
    comments: dict[int, str] = {}
    for token in tokenize.generate_tokens(io.StringIO(source).readline):
        if token.type == tokenize.COMMENT:
            comments[token.start[0]] = token.string.lstrip("#").strip()
    return comments


def _is_comment_line(line: str) -> bool:
    return line.lstrip().startswith("#")


def _block_above(lineno: int, lines: list[str], comments: dict[int, str]) -> list[str]:
    """The comment-only lines directly above line `lineno` (1-based), top to bottom."""
    block: list[str] = []
    line = lineno - 1
    while line >= 1 and _is_comment_line(lines[line - 1]) and line in comments:
        block.insert(0, comments[line])
        line -= 1
    return block


def field_description(model: type, name: str) -> str:
    """The field's description, or the comment of the class in the model's MRO that declares it."""
    info = model.model_fields[name]
    if info.description:
        return info.description
    for cls in model.__mro__:
        if name in cls.__dict__.get("__annotations__", {}):
            return class_comments(cls).get(name, "")
    return ""
