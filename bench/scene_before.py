"""The scene service as it was before a given commit, loaded from git next to today's, for bench_scene's baseline.

`git archive` writes services/scene of that revision to a temporary folder, which is imported as the package
scene_before_<rev>: its modules import each other relatively and the rest of coopdrive (protobuf types, road map)
as it is today, so the old pipeline runs in the same process and on the same inputs as the new one.
"""

from __future__ import annotations

import atexit
import importlib
import importlib.util
import io
import shutil
import subprocess
import sys
import tarfile
import tempfile
from pathlib import Path
from types import ModuleType

REPO = Path(__file__).resolve().parents[1]
SCENE_DIR = "services/scene"


def load(revision: str) -> ModuleType | None:
    """The fusion module of services/scene at revision, or None when git or that revision is not at hand."""
    try:
        archive = subprocess.run(["git", "-C", str(REPO), "archive", revision, SCENE_DIR],
                                 capture_output=True, check=True).stdout
    except (OSError, subprocess.CalledProcessError):
        return None
    folder = Path(tempfile.mkdtemp(prefix="scene_before_"))
    atexit.register(shutil.rmtree, folder, ignore_errors=True)
    with tarfile.open(fileobj=io.BytesIO(archive)) as tar:
        tar.extractall(folder, filter="data")
    name = f"scene_before_{revision[:12]}"
    package_dir = folder / SCENE_DIR
    spec = importlib.util.spec_from_file_location(name, package_dir / "__init__.py",
                                                  submodule_search_locations=[str(package_dir)])
    package = importlib.util.module_from_spec(spec)
    sys.modules[name] = package
    spec.loader.exec_module(package)
    return importlib.import_module(f"{name}.fusion")
