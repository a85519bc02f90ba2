"""Issue 25 acceptance, run as a user would: a v2x service process with the deployed config (deploy/config/v2x.yaml)
and a gateway process, on a Zenoh endpoint and radio-box UDP ports of their own; `coopdrive v2x replay` feeds
the service the real signed capture; the CAMs come out on v2x/cam and the gateway's /v2x/stations shows the
passenger car as signed and verified.

The capture is from 2023, and a CAM's generationDeltaTime only tells the time within 65.5 s: judged on today's
clock its age is anything in +-32 s. So the service runs with the deployed config plus the test's ports and a
plausibility window wide enough for an old capture (`plausibility.max_age_s`, `max_future_s`).
"""

import queue
import time
from pathlib import Path

import httpx
import pytest

from coopdrive.bus import Bus, BusConfig
from coopdrive.launch.ports import free_tcp_port, free_udp_ports
from tests.shared_data import shared_file

REPOSITORY = Path(__file__).resolve().parents[3]
SIGNED = "v2x/considerit_signed_testvectors.pcap"
CAR_STATION_ID, CAR_SPEED_MPS = 3141730734, 9.71
RSU_STATION_ID = 12816437
OLD_CAPTURE_WINDOW_S = 40.0
DEADLINE_S = 60.0
POLL_S = 0.2
# Before branch v2xdec: mode off without a PKI refuses secured packets, and the car's envelope (encoded by another
# stack's schema) is refused as not canonical.
UNREAD_SIGNED_REASONS = {"secured_packet_unsupported", "malformed_security_envelope"}


def wait_for(condition, what: str, deadline_s: float = DEADLINE_S):
    end = time.monotonic() + deadline_s
    while time.monotonic() < end:
        value = condition()
        if value:
            return value
        time.sleep(POLL_S)
    raise AssertionError(f"timed out waiting for {what}")


def stations_of(http: httpx.Client) -> dict:
    try:
        response = http.get("/v2x/stations")
    except httpx.TransportError:
        return {}
    return response.json() if response.status_code == 200 else {}


def test_the_deployed_v2x_service_fed_the_signed_capture_publishes_the_cams_and_the_gateway_shows_them_signed(
        endpoint, spawn):
    listen_port, radio_port = free_udp_ports(2)
    gateway_port = free_tcp_port()
    hub = Bus(BusConfig(listen=[endpoint]))
    cams: queue.Queue = queue.Queue()
    statuses: queue.Queue = queue.Queue()
    hub.subscribe("ego", "v2x/cam", lambda envelope: cams.put(envelope.message))
    hub.subscribe("ego", "v2x/status", lambda envelope: statuses.put(envelope.message))
    v2x = spawn("service", "v2x", "--config", str(REPOSITORY / "deploy/config/v2x.yaml"), "--vehicle", "ego",
                "--connect", endpoint, "--set", "link.listen_host=127.0.0.1",
                "--set", f"link.listen_port={listen_port}",
                "--set", "link.radio_host=127.0.0.1", "--set", f"link.radio_port={radio_port}",
                "--set", f"plausibility.max_age_s={OLD_CAPTURE_WINDOW_S}",
                "--set", f"plausibility.max_future_s={OLD_CAPTURE_WINDOW_S}")
    gateway = spawn("service", "gateway", "--config", str(REPOSITORY / "deploy/config/gateway.yaml"),
                    "--vehicle", "ego", "--connect", endpoint, "--set", "host=127.0.0.1",
                    "--set", f"port={gateway_port}")
    try:
        with httpx.Client(base_url=f"http://127.0.0.1:{gateway_port}", timeout=5.0) as http:
            # the service is up (it publishes its status) and the gateway answers: now the radio box may talk
            wait_for(lambda: not statuses.empty(), "the v2x service's first status")
            wait_for(lambda: "stations" in stations_of(http), "the gateway")
            replay = spawn("v2x", "replay", str(shared_file(SIGNED)), "--address", "127.0.0.1",
                           "--port", str(listen_port), "--rate", "10")
            assert replay.wait(timeout=30) == 0, replay.stderr.read()
            last_status = wait_for(lambda: _status_after_packets(statuses, 4), "a status counting the 4 packets")
            assert not UNREAD_SIGNED_REASONS & set(last_status.rejected_by_reason), last_status.rejected_by_reason
            received: list = []
            wait_for(lambda: len(_drain(cams, received)) >= 2, "both signed CAMs on v2x/cam")
            car = next(cam for cam in received if cam.station_id == CAR_STATION_ID)
            assert car.high_frequency.speed_mps == pytest.approx(CAR_SPEED_MPS, abs=0.01)
            assert {cam.station_id for cam in received} == {CAR_STATION_ID, RSU_STATION_ID}
            shown = wait_for(lambda: _station(stations_of(http), CAR_STATION_ID), "the car on /v2x/stations")
            assert (shown["signed"], shown["verified"]) == (True, True), shown
            assert shown["messages_signed"] == shown["messages_verified"] == 1
        assert v2x.poll() is None and gateway.poll() is None
    finally:
        hub.close()


def _drain(messages: queue.Queue, into: list) -> list:
    while not messages.empty():
        into.append(messages.get())
    return into


def _status_after_packets(statuses: queue.Queue, packets: int):
    latest = None
    while not statuses.empty():
        latest = statuses.get()
    return latest if latest is not None and latest.packets_received >= packets else None


def _station(view: dict, station_id: int) -> dict | None:
    return next((s for s in view.get("stations", []) if s["station_id"] == station_id), None)
