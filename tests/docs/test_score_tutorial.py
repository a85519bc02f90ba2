"""The tutorial docs/tutorials/score-a-drive.md, run as written: every `sh` block's command, in order, on the real
RAV4 data (../shared/data beside the checkout is wherever the shared data are), and what the text claims of it."""

import json
import re
import shlex
import subprocess
import sys
from pathlib import Path

from tests.shared_data import shared_data_dir

REPOSITORY = Path(__file__).resolve().parents[2]
TUTORIAL = REPOSITORY / "docs" / "tutorials" / "score-a-drive.md"
SH_BLOCK = re.compile(r"```sh\n(.*?)```", re.DOTALL)


def tutorial_commands() -> list[list[str]]:
    commands = []
    for block in SH_BLOCK.findall(TUTORIAL.read_text()):
        text = block.replace("\\\n", " ").replace("../shared/data", str(shared_data_dir()))
        commands += [shlex.split(line) for line in text.splitlines() if line.strip()]
    return commands


def test_the_scoring_tutorial_s_commands_run_and_give_the_figures_its_text_claims(tmp_path):
    commands = tutorial_commands()
    assert [command[:2] for command in commands] == [["coopdrive", "import"], ["coopdrive", "replay"],
                                                     ["coopdrive", "score"]]
    outputs = []
    for command in commands:
        # Files the tutorial writes go to a scratch folder; the repository's own (deploy/) are read where they are.
        args = [str(tmp_path / arg) if arg.endswith((".mcap", ".json")) else arg for arg in command[1:]]
        result = subprocess.run([sys.executable, "-m", "coopdrive.cli", *args], capture_output=True, text=True,
                                timeout=300, cwd=REPOSITORY)
        assert result.returncode == 0, f"{shlex.join(command)}:\n{result.stdout}\n{result.stderr}"
        outputs.append(result.stdout)
    assert "geolocation counted:" in outputs[1] and "CAN frames: 17938 received" in outputs[1]
    figures = json.loads((tmp_path / "score.json").read_text())
    fixes = next(score for score in figures["scores"] if score["name"] == "fixes")
    assert round(fixes["at_stamped_times"]["rms_m"], 2) == 1.96
    assert round(fixes["at_best_fit_offset"]["rms_m"], 2) == 0.42
    assert round(fixes["best_fit_offset_s"], 3) == 0.111
