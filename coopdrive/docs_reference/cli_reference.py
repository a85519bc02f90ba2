"""The command-line reference: every command and subcommand of an argparse parser, walked recursively, with each
argument's help, default and choices. Built from `coopdrive.cli.build_parser()`, so a new flag or subcommand is in
the reference as soon as it is in the parser."""

from __future__ import annotations

import argparse
from dataclasses import dataclass
from typing import Iterator

from coopdrive.docs_reference.markdown_table import cell, code, table

# Usage lines are wrapped at this width whatever the terminal that builds the docs.
USAGE_WIDTH = 100


@dataclass(frozen=True)
class Command:
    path: tuple[str, ...]  # ("coopdrive", "v2x", "decode")
    parser: argparse.ArgumentParser
    help: str

    @property
    def name(self) -> str:
        return " ".join(self.path)


def commands(parser: argparse.ArgumentParser, path: tuple[str, ...] = (), help_text: str = "") -> Iterator[Command]:
    """The parser and every subcommand under it, depth first, in the order they were added."""
    path = path or (parser.prog,)
    yield Command(path, parser, help_text or parser.description or "")
    for action in parser._actions:
        if isinstance(action, argparse._SubParsersAction):
            helps = {choice.dest: choice.help or "" for choice in action._choices_actions}
            for name, subparser in action.choices.items():
                yield from commands(subparser, (*path, name), helps.get(name, ""))


def _is_documented(action: argparse.Action) -> bool:
    return action.help != argparse.SUPPRESS and not isinstance(action, (argparse._HelpAction,
                                                                        argparse._SubParsersAction))


def _argument(action: argparse.Action) -> str:
    if not action.option_strings:
        return action.metavar or action.dest
    takes_value = action.nargs != 0
    value = f" {action.metavar or action.dest.upper()}" if takes_value else ""
    return ", ".join(f"{option}{value}" for option in action.option_strings)


def _default(action: argparse.Action) -> str:
    default = action.default
    if default in (None, argparse.SUPPRESS) or default == [] or isinstance(action, argparse._StoreTrueAction):
        return ""
    if isinstance(action, argparse._StoreFalseAction):
        return ""
    return str(default)


def _notes(action: argparse.Action) -> str:
    notes = []
    if action.option_strings and action.required:
        notes.append("required")
    if isinstance(action, argparse._AppendAction) or action.nargs in ("+", "*"):
        notes.append("repeatable" if isinstance(action, argparse._AppendAction) else "one or more")
    return ", ".join(notes)


def usage(parser: argparse.ArgumentParser) -> str:
    formatter = argparse.HelpFormatter(parser.prog, width=USAGE_WIDTH)
    formatter.add_usage(parser.usage, parser._actions, parser._mutually_exclusive_groups)
    return formatter.format_help().strip()


def command_markdown(command: Command) -> str:
    subcommands = [c for c in command.parser._actions if isinstance(c, argparse._SubParsersAction)]
    parts = [f"## `{command.name}`", "", cell(command.help), "", "```text", usage(command.parser), "```", ""]
    rows = [[code(_argument(a)), cell(a.help or ""), code(_default(a)),
             ", ".join(code(choice) for choice in a.choices or ()), cell(_notes(a))]
            for a in command.parser._actions if _is_documented(a)]
    if rows:
        parts += [table(["argument", "what it does", "default", "choices", "notes"], rows), ""]
    for action in subcommands:
        names = ", ".join(f"[`{name}`](#{_anchor((*command.path, name))})" for name in action.choices)
        parts += [f"Subcommands: {names}.", ""]
    return "\n".join(parts)


def _anchor(path: tuple[str, ...]) -> str:
    """The id Python-Markdown's toc gives a heading `` `coopdrive v2x decode` ``."""
    return "-".join(path).lower()


INTRO = """# Command line

Generated from `coopdrive.cli.build_parser()` when the documentation is built: every command, subcommand and
option the installed `coopdrive` accepts. `coopdrive COMMAND --help` prints the same at the terminal.
"""


def cli_markdown(parser: argparse.ArgumentParser) -> str:
    return "\n".join([INTRO, *(command_markdown(command) for command in commands(parser))])


def coopdrive_cli_markdown() -> str:
    from coopdrive.cli import build_parser

    return cli_markdown(build_parser())
