"""Our station on a live wire: the real v2x service on a raw link, with a Zenoh bus of its own, for the live tests
(tests/v2x/live) and tools/v2x_live_peer.sh. Run it where the interface is (inside a network namespace with
`ip netns exec NS`: a process there cannot reach the root namespace's 127.0.0.1, so it brings its own bus):

    python -m tests.v2x.live.our_station --config v2x.yaml --duration-s 10 [--speed-mps 10] [--denm]

It opens a Bus on a free port of 127.0.0.1, starts `coopdrive service v2x --vehicle ego --config FILE` connected to
it, publishes a moving ego/state at 10 Hz (so our CAMs carry a speed), optionally sends a DENM (see send_denms),
collects v2x/cam, v2x/denm, v2x/vam and v2x/status for the duration, stops the service and prints ONE JSON summary line.
With --go-on-stdin it prints `ready` once the service runs and starts when a line arrives on stdin.
"""

from __future__ import annotations

import argparse
import json
import os
import signal
import subprocess
import sys
import threading
import time
from pathlib import Path

import yaml
from google.protobuf import json_format

from coopdrive.bus import Bus, BusConfig
from coopdrive.launch.ports import free_tcp_port, loopback_endpoint
from coopdrive.services.gateway.views import station_reception
from coopdrive.services.v2x.config import V2xConfig
from coopdrive.v1 import ego_pb2
from tests.v2x.live.our_denm import DenmSender

VEHICLE = "ego"
EGO_PERIOD_S = 0.1
# How long the service may take to stop after SIGTERM before it is killed.
STOP_TIMEOUT_S = 10.0
# How long the service may take to publish its first status (imports, Zenoh, the link) on a loaded machine.
START_TIMEOUT_S = 60.0
STDERR_TAIL_LINES = 20
# The line a station prints when it can start the exchange (--go-on-stdin); flexstack_peer.py prints the same.
READY = "ready"


class Collected:
    """What the bus brought from our service, kept by the subscriber threads."""

    def __init__(self):
        self.lock = threading.Lock()
        self.cams: dict[int, dict] = {}
        self.denms: dict[int, dict] = {}
        self.vams: dict[int, dict] = {}
        self.status: dict | None = None
        # Each station's VAMs heard when the last status arrived: the station table that status lists counts those.
        self.vams_at_status: dict[str, int] = {}
        self.health_v2x: list[dict] = []
        self.started = threading.Event()

    @staticmethod
    def _heard_at(table: dict[int, dict], message) -> dict:
        """The station's entry, counted once more and at the message's reference position."""
        heard = table.setdefault(message.station_id, {"count": 0})
        heard["count"] += 1
        heard["latitude_deg"] = message.reference_position.latitude_deg
        heard["longitude_deg"] = message.reference_position.longitude_deg
        return heard

    def on_cam(self, envelope) -> None:
        cam = envelope.message
        with self.lock:
            heard = self._heard_at(self.cams, cam)
            heard["speed_mps"] = cam.high_frequency.speed_mps
            heard["protocol_version"] = cam.protocol_version

    def on_denm(self, envelope) -> None:
        denm = envelope.message
        with self.lock:
            heard = self.denms.setdefault(denm.station_id, {"count": 0})
            heard["count"] += 1
            heard["originating_station_id"] = denm.originating_station_id
            heard["termination"] = denm.termination
            heard["validity_duration_s"] = denm.validity_duration_s

    def on_vam(self, envelope) -> None:
        vam = envelope.message
        with self.lock:
            self._heard_at(self.vams, vam)["station_type"] = vam.station_type

    def on_status(self, envelope) -> None:
        with self.lock:
            self.status = json_format.MessageToDict(envelope.message, preserving_proto_field_name=True)
            self.vams_at_status = {str(k): v["count"] for k, v in self.vams.items()}
            # What the gateway's /health would show of it (the same function serves it there).
            self.health_v2x = [s.model_dump() for s in station_reception(envelope.message)]
        self.started.set()


def start_service(config_path: Path, endpoint: str) -> subprocess.Popen:
    return subprocess.Popen([sys.executable, "-m", "coopdrive.cli", "service", "v2x", "--vehicle", VEHICLE,
                             "--connect", endpoint, "--config", str(config_path)],
                            start_new_session=True, stdout=subprocess.DEVNULL, stderr=subprocess.PIPE, text=True)


def stop_service(process: subprocess.Popen) -> str:
    """Stops the service (SIGTERM, then SIGKILL) and returns the tail of what it wrote on stderr."""
    if process.poll() is None:
        process.send_signal(signal.SIGTERM)
    try:
        _, stderr = process.communicate(timeout=STOP_TIMEOUT_S)
    except subprocess.TimeoutExpired:
        os.killpg(process.pid, signal.SIGKILL)
        _, stderr = process.communicate()
    return "\n".join(stderr.strip().splitlines()[-STDERR_TAIL_LINES:])


def drive(bus: Bus, process: subprocess.Popen, duration_s: float, speed_mps: float,
          denms: DenmSender | None) -> None:
    """Publishes a vehicle driving east at speed_mps every EGO_PERIOD_S for duration_s (while the service runs)."""
    start_s = time.monotonic()
    while process.poll() is None and (elapsed_s := time.monotonic() - start_s) < duration_s:
        bus.publish(VEHICLE, "ego/state", ego_pb2.EgoState(x_m=speed_mps * elapsed_s, speed_mps=speed_mps))
        if denms is not None:
            denms.send_due(time.monotonic())
        time.sleep(EGO_PERIOD_S)


def run(config_path: Path, duration_s: float, speed_mps: float, send_denm: bool, go_on_stdin: bool) -> dict:
    config = V2xConfig.model_validate(yaml.safe_load(config_path.read_text()) or {})
    endpoint = loopback_endpoint(free_tcp_port())
    bus = Bus(BusConfig(listen=[endpoint]))
    collected = Collected()
    bus.subscribe(VEHICLE, "v2x/cam", collected.on_cam)
    bus.subscribe(VEHICLE, "v2x/denm", collected.on_denm)
    bus.subscribe(VEHICLE, "v2x/vam", collected.on_vam)
    bus.subscribe(VEHICLE, "v2x/status", collected.on_status)
    process = start_service(config_path, endpoint)
    denms = None
    try:
        wait_until_started(collected, process)
        if go_on_stdin:
            wait_for_go()
        if send_denm and process.poll() is None:
            denms = DenmSender(config, duration_s, time.monotonic())
        drive(bus, process, duration_s, speed_mps, denms)
    finally:
        returncode_while_running = process.poll()
        stderr_tail = stop_service(process)
        if denms is not None:
            denms.close()
        bus.close()
    with collected.lock:
        return {"station_id": config.station_id, "started": collected.started.is_set(),
                "service_exited_early": returncode_while_running is not None, "service_stderr": stderr_tail,
                "cams": {str(k): v for k, v in collected.cams.items()},
                "denms": {str(k): v for k, v in collected.denms.items()},
                "vams": {str(k): v for k, v in collected.vams.items()},
                "denms_sent": denms.sent if denms is not None else 0, "status": collected.status or {},
                "vams_at_status": collected.vams_at_status,
                "health_v2x": collected.health_v2x}


def wait_until_started(collected: Collected, process: subprocess.Popen) -> None:
    """Until the service's first status, its exit (a missing interface: its one line is in the summary) or
    START_TIMEOUT_S."""
    deadline = time.monotonic() + START_TIMEOUT_S
    while not collected.started.wait(EGO_PERIOD_S) and process.poll() is None and time.monotonic() < deadline:
        pass


def wait_for_go() -> None:
    """Says `ready` on stdout and waits for a line on stdin: the live tests start the exchange on both stations at
    once, whichever took longer to start (seconds apart on a loaded machine)."""
    print(READY, flush=True)
    sys.stdin.readline()


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--config", type=Path, required=True, help="the v2x service's config (a raw link)")
    parser.add_argument("--duration-s", type=float, default=10.0)
    parser.add_argument("--speed-mps", type=float, default=10.0)
    parser.add_argument("--denm", action="store_true", help="also send a DENM (a stationary vehicle) on the link")
    parser.add_argument("--go-on-stdin", action="store_true",
                        help=f"once the service runs, print {READY!r} and start when a line arrives on stdin")
    args = parser.parse_args()
    print(json.dumps(run(args.config, args.duration_s, args.speed_mps, args.denm, args.go_on_stdin)), flush=True)


if __name__ == "__main__":
    main()
