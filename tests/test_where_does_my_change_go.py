"""docs/where-does-my-change-go.md names only places that exist: each path it quotes is a file or folder of the
repository (a pattern such as tests/geolocation/test_nmea_*.py matches one at least; a bare file name lives in
a folder its row names, or beside a file it names)."""

import re
from pathlib import Path

ROOT = Path(__file__).parents[1]
PAGE = ROOT / "docs" / "where-does-my-change-go.md"
QUOTED = re.compile(r"`([^`]+)`")


def quoted_paths(text: str) -> list[str]:
    """The quoted words that name a file or folder: with a slash or a file suffix, not a command or a placeholder."""
    names = [name.split(" ")[0] for name in QUOTED.findall(text)]
    return [name for name in names if ("/" in name or name.endswith((".py", ".yaml", ".md")))
            and "<" not in name and not name.startswith(("python", "coopdrive "))]


def exists(name: str, row: str) -> bool:
    if "/" in name:
        return any(ROOT.glob(name.rstrip("/")))
    places = [ROOT / found for found in quoted_paths(row) if "/" in found]
    folders = [place if place.is_dir() else place.parent for place in places]
    return any((folder / name).exists() for folder in folders)


def test_every_place_the_page_names_exists():
    rows = [line for line in PAGE.read_text(encoding="utf-8").splitlines() if line.startswith("| ")]
    missing = [name for row in rows for name in quoted_paths(row) if not exists(name, row)]
    assert rows and missing == []


def test_the_check_finds_a_place_that_does_not_exist():
    row = "| x | `coopdrive/runtime` (`runner.py`, `no_such_part.py`) | `tests/nowhere` |"
    assert [name for name in quoted_paths(row) if not exists(name, row)] == ["no_such_part.py", "tests/nowhere"]
