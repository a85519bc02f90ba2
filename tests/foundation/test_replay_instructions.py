"""bench.replay_instructions: instruction counts under callgrind, and the code of a revision importable beside today's."""

import os
import subprocess
import sys
from pathlib import Path

import pytest

from bench.replay_instructions import CallgrindError, instructions
from bench.tree_at_revision import RevisionError, tree_at_revision
from tests.system_packages import needs

REPO = Path(__file__).resolve().parents[2]
FIXED_HASHES = {**os.environ, "PYTHONHASHSEED": "0"}
needs_valgrind = needs("valgrind")


@needs_valgrind
def test_the_same_command_counts_the_same_instructions_twice_and_more_work_counts_more():
    idle = [sys.executable, "-S", "-c", "pass"]
    busy = [sys.executable, "-S", "-c", "sum(range(200_000))"]
    first, second = instructions(idle, FIXED_HASHES), instructions(idle, FIXED_HASHES)
    assert first == second > 0
    assert instructions(busy, FIXED_HASHES) > first + 10_000_000


@needs_valgrind
def test_a_command_that_fails_under_callgrind_is_an_error_that_says_so():
    with pytest.raises(CallgrindError, match="failed under callgrind"):
        instructions([sys.executable, "-S", "-c", "raise SystemExit(3)"])


def test_the_tree_of_a_revision_imports_its_own_services_maps_and_generated_messages(tmp_path):
    tree = tree_at_revision("HEAD", tmp_path / "tree", REPO)
    probe = ("import coopdrive.services.scene.track as track, coopdrive.maps as maps, coopdrive.v1.scene_pb2 as pb;"
             "print(track.__file__, maps.__file__, pb.__file__)")
    # From the tree's folder, as the bench runs it: `python -c` and `-m` put the working directory first on the path.
    result = subprocess.run([sys.executable, "-c", probe], capture_output=True, text=True, check=True, cwd=tree,
                            env={**os.environ, "PYTHONPATH": str(tree)})
    paths = [Path(p) for p in result.stdout.split()]
    assert len(paths) == 3 and all(str(p).startswith(str(tree)) for p in paths)


def test_a_revision_git_does_not_know_is_named_in_the_error(tmp_path):
    with pytest.raises(RevisionError, match="no-such-revision"):
        tree_at_revision("no-such-revision", tmp_path / "tree", REPO)
