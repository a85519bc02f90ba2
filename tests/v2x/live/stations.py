"""The stations of the live tests: our v2x service's config on a raw link and the argv of each station process.

GN version 1 and CAM/DENM protocol version 2 are set explicitly: today's defaults are GCDC's (GN 0, CAM v1), which
FlexStack cannot decode (the note /work/shared/notes/v2x-peers.md); issue 71 makes these the defaults in a
separate step, after which the two keys below can go.
"""

from __future__ import annotations

import subprocess
import sys
from pathlib import Path

import pytest
import yaml

from tests.system_packages import MISSING

ROOT = Path(__file__).resolve().parents[3]
PEER_PYTHON = ROOT / ".venv-peers" / "bin" / "python"
PEER_SCRIPT = Path(__file__).with_name("flexstack_peer.py")
# Long enough for a few dozen CAMs each way at FlexStack's 2.5 Hz (a vehicle at 10 m/s moves its 4 m) and ours.
EXCHANGE_S = 10.0
SPEED_MPS = 10.0
CERTS_TIMEOUT_S = 120.0


def needs_peer_env() -> Path:
    """FlexStack's interpreter; skips naming the script that makes it. `make test` and CI run that script first, so
    under CI this skip fails like a missing system package's (tests/system_packages.py)."""
    if not PEER_PYTHON.is_file():
        pytest.skip(f"{MISSING} no {PEER_PYTHON.relative_to(ROOT)} (make it with tools/peer_env.sh)")
    return PEER_PYTHON


def our_config(folder: Path, interface: str, station_id: int, mac: str, **settings) -> Path:
    """Our service's config on the interface, with the default profile (etsi: GN 1, CAM v2, CAMs by dynamics) and
    no iCLCM (GCDC's own message)."""
    config = {"link": {"type": "raw", "interface": interface}, "station_id": station_id,
              "vehicle_mac": mac, "send_iclcm": False, **settings}
    path = folder / f"v2x-{station_id}.yaml"
    path.write_text(yaml.safe_dump(config))
    return path


def our_station(config: Path, *options: str, duration_s: float = EXCHANGE_S) -> list[str]:
    """The argv of our station (our_station.py) with the service on the config's interface."""
    return [sys.executable, "-m", "tests.v2x.live.our_station", "--config", str(config), "--duration-s",
            str(duration_s), "--speed-mps", str(SPEED_MPS), "--go-on-stdin", *options]


def flexstack_station(interface: str, station_id: int, mac: str, *options: str,
                      duration_s: float = EXCHANGE_S) -> list[str]:
    """The argv of a FlexStack station (flexstack_peer.py run) on the interface."""
    return [str(PEER_PYTHON), str(PEER_SCRIPT), "run", "--interface", interface, "--station-id", str(station_id),
            "--mac", mac, "--duration-s", str(duration_s), "--speed-mps", str(SPEED_MPS), "--go-on-stdin", *options]


def make_flexstack_chain(directory: Path) -> Path:
    """A certificate chain made by FlexStack's own code, in its own process."""
    subprocess.run([str(PEER_PYTHON), str(PEER_SCRIPT), "make-certs", str(directory)], check=True,
                   capture_output=True, timeout=CERTS_TIMEOUT_S)
    return directory


def ours_ran(summary: dict) -> dict:
    """The summary of our station, after checking that its service ran the whole exchange (else its stderr)."""
    assert summary["started"] and not summary["service_exited_early"], summary["service_stderr"]
    return summary
