"""The `coopdrive ...` command lines of the documentation's code blocks, and whether each still parses: a renamed or
misspelled flag in the README or a docs page is a test failure naming the file and line, not a reader's surprise."""

from __future__ import annotations

import argparse
import contextlib
import io
import re
import shlex
from dataclasses import dataclass
from typing import Iterator

PROGRAM = "coopdrive"
FENCE = re.compile(r"^\s*(```|~~~)")
ENV_ASSIGNMENT = re.compile(r"^[A-Za-z_][A-Za-z0-9_]*=")
# Where the command's own arguments end: a pipe, a list operator or a redirection.
SHELL_OPERATORS = ("|", "||", "&&", ";", "&")
REDIRECTION = re.compile(r"^(\d*>>?|<|\d*>&\d*)")


@dataclass(frozen=True)
class DocumentedCommand:
    source: str
    line: int  # 1-based, the command's first line
    text: str  # as written, continuation lines joined
    args: tuple[str, ...]  # what follows `coopdrive`

    @property
    def where(self) -> str:
        return f"{self.source}:{self.line}: {self.text}"


def code_block_lines(markdown: str) -> Iterator[tuple[int, str]]:
    """(line number, line) of every line inside a fenced code block."""
    fence = ""
    for number, line in enumerate(markdown.splitlines(), start=1):
        match = FENCE.match(line)
        if match and (not fence or match.group(1) == fence):
            fence = "" if fence else match.group(1)
        elif fence:
            yield number, line


def _logical_lines(markdown: str) -> Iterator[tuple[int, str]]:
    """Code block lines with their `\\` continuations joined, comment lines left out."""
    start, pending = 0, ""
    for number, line in code_block_lines(markdown):
        stripped = line.strip()
        if not pending and (not stripped or stripped.startswith("#")):
            continue
        start = start if pending else number
        if stripped.endswith("\\"):
            pending += stripped[:-1] + " "
            continue
        yield start, pending + stripped
        pending = ""
    if pending:
        yield start, pending


def command_args(line: str) -> tuple[str, ...] | None:
    """The arguments after `coopdrive` when the line runs it (after any VAR=value prefix), else None."""
    try:
        tokens = shlex.split(line, comments=True)
    except ValueError:
        return None
    while tokens and ENV_ASSIGNMENT.match(tokens[0]):
        tokens = tokens[1:]
    if not tokens or tokens[0] != PROGRAM:
        return None
    args = []
    for token in tokens[1:]:
        if token in SHELL_OPERATORS or REDIRECTION.match(token):
            break
        args.append(token)
    return tuple(args)


def documented_commands(markdown: str, source: str) -> list[DocumentedCommand]:
    commands = []
    for number, line in _logical_lines(markdown):
        args = command_args(line)
        if args is not None:
            commands.append(DocumentedCommand(source, number, line, args))
    return commands


def parse_error(parser: argparse.ArgumentParser, command: DocumentedCommand) -> str:
    """"" when the parser takes the command's arguments, else argparse's message."""
    stderr = io.StringIO()
    try:
        with contextlib.redirect_stderr(stderr), contextlib.redirect_stdout(io.StringIO()):
            parser.parse_args(list(command.args))
    except SystemExit as stop:
        if stop.code not in (0, None):
            return stderr.getvalue().strip().splitlines()[-1] if stderr.getvalue().strip() else f"exit {stop.code}"
    return ""
