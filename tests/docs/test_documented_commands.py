"""Every `coopdrive ...` command line in a code block of the README and the docs pages parses with the command line's
own parser: a renamed or misspelled flag fails here, naming the file and line, before a reader meets it."""

from pathlib import Path

import pytest

from coopdrive.cli import build_parser
from coopdrive.docs_reference.documented_commands import command_args, documented_commands, parse_error

ROOT = Path(__file__).resolve().parents[2]
# The README lists the ten commands a team uses most, each in a code block as well.
MIN_README_COMMANDS = 10


def documentation_files() -> list[Path]:
    return [ROOT / "README.md", *sorted((ROOT / "docs").rglob("*.md"))]


def failures(commands) -> list[str]:
    parser = build_parser()
    return [f"{command.where} -> {error}" for command in commands if (error := parse_error(parser, command))]


@pytest.fixture(scope="module")
def every_documented_command():
    return [command for path in documentation_files()
            for command in documented_commands(path.read_text(encoding="utf-8"), str(path.relative_to(ROOT)))]


def test_every_coopdrive_command_of_the_readme_and_the_docs_parses(every_documented_command):
    assert failures(every_documented_command) == []


def test_the_readme_documents_the_commands_a_team_uses_most(every_documented_command):
    readme = [command for command in every_documented_command if command.source == "README.md"]
    assert len(readme) >= MIN_README_COMMANDS
    assert {command.args[0] for command in readme} >= {"run", "record", "import", "replay", "v2x", "foxglove"}


FAKE_PAGE = """# A page

```sh
coopdrive run follow --seed 1 --reprot out/x      # misspelled
coopdrive replay drive.mcap --service geolocation \\
    --set vehicle_can=car.yaml --out replayed.mcap
# coopdrive run follow --not-a-flag                (a comment line)
```

    coopdrive run follow --indented-prose-is-not-a-block
"""


def test_a_misspelled_flag_in_a_page_fails_naming_its_file_line_and_the_flag():
    commands = documented_commands(FAKE_PAGE, "docs/fake.md")
    assert [command.line for command in commands] == [4, 5]
    [failure] = failures(commands)
    assert failure.startswith("docs/fake.md:4: coopdrive run follow --seed 1 --reprot out/x")
    assert "unrecognized arguments: --reprot out/x" in failure


def test_continuation_lines_are_joined_into_one_command():
    [_, replay] = documented_commands(FAKE_PAGE, "docs/fake.md")
    assert replay.args == ("replay", "drive.mcap", "--service", "geolocation", "--set", "vehicle_can=car.yaml",
                           "--out", "replayed.mcap")


@pytest.mark.parametrize("line, args", [
    ("coopdrive export a.mcap --topic ego/state > ego.csv", ("export", "a.mcap", "--topic", "ego/state")),
    ("coopdrive v2x decode c.pcap --json | jq .summary", ("v2x", "decode", "c.pcap", "--json")),
    ("COOPDRIVE_PROFILE_DIR=out/prof coopdrive run follow 2>&1", ("run", "follow")),
    ("coopdrive scenarios && echo done", ("scenarios",)),
    ("docker compose --profile desk up", None),
    ("python -m coopdrive.visual.layout --vehicle a1", None),
])
def test_environment_prefixes_pipes_redirections_and_other_programs_are_handled(line, args):
    assert command_args(line) == args
