"""The project's code as it was at a git revision, importable beside today's: `PYTHONPATH=FOLDER python -m ...` runs
that revision's framework, services, maps and scenarios.

`git archive` writes the folders to FOLDER, and the subpackages the install maps elsewhere (setup.py: services/ as
coopdrive.services, maps/ and scenarios/ as coopdrive.maps and coopdrive.scenarios) are linked into FOLDER/coopdrive
where a plain import finds them before the editable install's finder. The protobuf modules are generated at install,
never checked in, so today's are copied: only where the revision's proto/ is today's, else the old code would run on
other messages.
"""

from __future__ import annotations

import io
import shutil
import subprocess
import tarfile
from pathlib import Path

FOLDERS = ("coopdrive", "services", "maps", "scenarios", "proto")
# Installed as coopdrive.<name> from the folder <name> at the top of the repository.
MAPPED_SUBPACKAGES = ("services", "maps", "scenarios")
PROTOBUF_PACKAGE = Path("coopdrive") / "v1"


class RevisionError(RuntimeError):
    pass


def tree_at_revision(revision: str, folder: Path, repository: Path) -> Path:
    """FOLDER with the code of `revision`; RevisionError when git cannot give it or its messages differ from today's."""
    def git(*arguments: str) -> subprocess.CompletedProcess:
        return subprocess.run(["git", "-C", str(repository), *arguments], capture_output=True)

    archive = git("archive", revision, *FOLDERS)
    if archive.returncode != 0:
        raise RevisionError(f"git archive {revision}: {archive.stderr.decode().strip()}")
    if git("diff", "--quiet", revision, "--", "proto").returncode != 0:
        raise RevisionError(f"proto/ changed since {revision}: its protobuf modules cannot be today's")
    folder.mkdir(parents=True, exist_ok=True)
    with tarfile.open(fileobj=io.BytesIO(archive.stdout)) as tar:
        tar.extractall(folder, filter="data")
    for name in MAPPED_SUBPACKAGES:
        (folder / "coopdrive" / name).symlink_to(Path("..") / name, target_is_directory=True)
    for generated in (repository / PROTOBUF_PACKAGE).glob("*_pb2.py*"):
        shutil.copy2(generated, folder / PROTOBUF_PACKAGE / generated.name)
    return folder
