"""The documentation site builds with `mkdocs build --strict`, as `make docs` builds it: every page of the nav, the
generated reference among them, and every link between them. A broken link fails the build, naming the page."""

import os
import shutil
import subprocess
import sys
from pathlib import Path

ROOT = Path(__file__).resolve().parents[2]
BUILD_TIMEOUT_S = 240


def mkdocs_build(config: Path, site: Path) -> subprocess.CompletedProcess:
    return subprocess.run([sys.executable, "-m", "mkdocs", "build", "--strict", "--config-file", str(config),
                           "--site-dir", str(site)], capture_output=True, text=True, timeout=BUILD_TIMEOUT_S,
                          env={**os.environ, "NO_MKDOCS_2_WARNING": "1"})


def test_the_site_builds_strictly_with_the_generated_reference_pages(tmp_path):
    built = mkdocs_build(ROOT / "mkdocs.yml", tmp_path / "site")
    assert built.returncode == 0, built.stderr
    reference = tmp_path / "site" / "reference"
    for page in ("cli", "config", "scenario-file", "vehicle-can-adapter", "topics", "metrics"):
        assert (reference / f"{page}.html").is_file()
    assert "coopdrive replay" in (reference / "cli.html").read_text(encoding="utf-8")
    assert (tmp_path / "site" / "index.html").is_file()


def test_a_broken_link_fails_the_strict_build_naming_the_page(tmp_path):
    """The site's own settings (theme, validation, extensions) on one of its pages, which builds clean until it is
    given a broken link: the generated reference and the nav are left out, so a build takes a second."""
    settings = (ROOT / "mkdocs.yml").read_text(encoding="utf-8")
    settings = settings.split("\nnav:\n", 1)[0].replace("hooks:\n  - docs/hooks/reference.py\n", "")
    (tmp_path / "mkdocs.yml").write_text(settings, encoding="utf-8")
    shutil.copytree(ROOT / "docs" / "stylesheets", tmp_path / "docs" / "stylesheets")
    page = tmp_path / "docs" / "lockstep.md"
    shutil.copy(ROOT / "docs" / "lockstep.md", page)
    assert mkdocs_build(tmp_path / "mkdocs.yml", tmp_path / "site").returncode == 0
    page.write_text(page.read_text(encoding="utf-8") + "\nSee [the missing page](no-such-page.md).\n",
                    encoding="utf-8")
    built = mkdocs_build(tmp_path / "mkdocs.yml", tmp_path / "site")
    assert built.returncode != 0
    assert "lockstep.md" in built.stderr and "no-such-page.md" in built.stderr
