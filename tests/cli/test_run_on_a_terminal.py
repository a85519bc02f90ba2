"""`coopdrive run` on a terminal, as `make run` runs it: a progress line while it runs, then the story on one
screen naming the recording and the next commands."""

import os
import pty
import re
import subprocess
import sys

import pytest

pytestmark = pytest.mark.whole_run

# The issue's bound for `make run`'s output: one screen.
SCREEN_LINES = 30
RUN_TIMEOUT_S = 300


def test_a_run_on_a_terminal_shows_its_progress_then_a_story_on_one_screen(tmp_path):
    recording = tmp_path / "follow.mcap"
    command = [sys.executable, "-m", "coopdrive.cli", "run", "follow", "--duration", "3", "--record", str(recording)]
    controller, terminal = pty.openpty()
    process = subprocess.Popen(command, stdin=subprocess.DEVNULL, stdout=terminal, stderr=terminal,
                               env={**os.environ, "COLUMNS": "120"}, start_new_session=True)
    os.close(terminal)
    output = b""
    while True:
        try:
            chunk = os.read(controller, 65536)
        except OSError:  # the terminal closes with the process
            break
        if not chunk:
            break
        output += chunk
    assert process.wait(timeout=RUN_TIMEOUT_S) == 0, output.decode(errors="replace")
    text = re.sub(r"\x1b\[[0-9;]*m", "", output.decode())
    assert "simulated 3.0 of 3.0 s" in text
    # What stays on the screen of each line: the progress line is redrawn after a carriage return, then cleared.
    screen = [line.rsplit("\r", 1)[-1] for line in text.replace("\r\n", "\n").split("\n")]
    story = [line for line in screen if line.strip()]
    assert story[0] == "PASS  follow (seed 1)"
    assert len(story) < SCREEN_LINES
    assert any(str(recording) in line for line in story)
    assert any(f"coopdrive replay {recording} --service control" in line for line in story)
