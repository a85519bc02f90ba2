"""Commit: the commit a benchmark run measured, and whether the tree had changes besides it."""

from __future__ import annotations

import subprocess
from dataclasses import dataclass
from pathlib import Path

REPOSITORY = Path(__file__).resolve().parents[1]


@dataclass
class Commit:
    sha: str
    dirty: bool

    @classmethod
    def now(cls) -> Commit:
        """HEAD of the repository, and whether its tree has changes (bench/results.json is ignored)."""
        def git(*arguments: str) -> str:
            return subprocess.run(["git", *arguments], cwd=REPOSITORY, capture_output=True, text=True,
                                  check=True).stdout.strip()
        try:
            return cls(git("rev-parse", "HEAD"), bool(git("status", "--porcelain")))
        except (OSError, subprocess.CalledProcessError):
            return cls("unknown (no git)", True)

    def describe(self) -> str:
        return self.sha[:12] + (" with changes" if self.dirty else "")
