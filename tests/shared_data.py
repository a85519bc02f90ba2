"""Where the real recordings of ../shared/data are: beside the clone in CI, or named by COOPDRIVE_SHARED_DATA.

Tests that read them fail (not skip) when they are missing: they are the project's evidence against real devices.
"""

import os
from pathlib import Path

REPOSITORY = Path(__file__).resolve().parents[1]
_CANDIDATES = (REPOSITORY.parent / "shared" / "data", Path("/work/shared/data"))


def shared_data_dir() -> Path:
    named = os.environ.get("COOPDRIVE_SHARED_DATA")
    candidates = (Path(named),) if named else _CANDIDATES
    for candidate in candidates:
        if (candidate / "README.md").is_file():
            return candidate
    raise FileNotFoundError(f"the real recordings are not at any of {[str(c) for c in candidates]}: "
                            "clone the repository beside shared/ or set COOPDRIVE_SHARED_DATA")


def shared_file(relative: str) -> Path:
    """A file of shared/data, e.g. shared_file('gnss/gpsd_hemi.log')."""
    path = shared_data_dir() / relative
    if not path.is_file():
        raise FileNotFoundError(f"{relative} is not in {shared_data_dir()}")
    return path
