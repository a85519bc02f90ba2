"""A GatewayService on a loopback port with an in-memory context (no Zenoh), and bus messages to feed it."""

import logging
import signal
import subprocess
import sys
import time
from pathlib import Path

import httpx
import pytest

from coopdrive.launch.ports import free_tcp_port
from coopdrive.runtime.testing import MemoryContext
from coopdrive.services.gateway.service import GatewayService
from coopdrive.v1 import actuation_pb2, ego_pb2, header_pb2, planner_pb2, scene_pb2, v2x_pb2

# Generous: a loaded 2-core machine may be slow to schedule the server thread.
REQUEST_TIMEOUT_S = 20.0
OPERATOR_TOKEN = "operator-secret-1"
OBSERVER_TOKEN = "observer-secret-1"
TOKENS = {"alice": {"token": OPERATOR_TOKEN, "role": "operator"},
          "dashboard": {"token": OBSERVER_TOKEN, "role": "observer"}}


class Gateway:
    def __init__(self, service: GatewayService, ctx: MemoryContext, client: httpx.Client):
        self.service, self.ctx, self.http = service, ctx, client
        self.port = service.config.port


@pytest.fixture
def make_gateway():
    started: list[Gateway] = []

    def make(**config) -> Gateway:
        ctx = MemoryContext(log=logging.getLogger("test.gateway"))
        service = GatewayService(GatewayService.Config(port=free_tcp_port(), **config), ctx)
        service.start()
        client = httpx.Client(base_url=f"http://127.0.0.1:{service.config.port}", timeout=REQUEST_TIMEOUT_S)
        started.append(Gateway(service, ctx, client))
        return started[-1]

    yield make
    for gateway in started:
        gateway.http.close()
        gateway.service.stop()


def feed_a_following_vehicle(ctx: MemoryContext, clock_s: float = 10.0, speed_mps: float = 15.0) -> None:
    """One of each message the views read: ego at (100, 0) heading north, a lead car 30 m ahead with V2V."""
    ctx.clock.set(clock_s)
    ego = ego_pb2.EgoState(x_m=100.0, y_m=0.0, heading_rad=1.5707963267948966, speed_mps=speed_mps)
    ego.lane.matched, ego.lane.lane_width_m, ego.lane.lane_index = True, 3.5, 0
    ctx.deliver("ego/state", ego)
    scene = scene_pb2.Scene(has_forward_mio=True, forward_mio_id=7, has_mio=True, mio_id=7, ego_lane_index=0)
    lead = scene.objects.add(object_id=7, object_class=1, longitudinal_gap_m=30.0, v2v_trust=0.9)
    lead.position.x_m, lead.position.y_m, lead.position.confidence = 100.0, 34.0, 0.8
    lead.position.sources.extend([header_pb2.SENSOR_SOURCE_RADAR, header_pb2.SENSOR_SOURCE_V2V])
    lead.speed_mps.value, lead.speed_mps.confidence = 14.0, 0.7
    lead.accel_mps2.confidence = -1.0
    lead.station_id.value, lead.station_id.confidence = 4242, 1.0
    scene.station_trust.add(station_id=666, trust=0.05, untrusted_signer=True, security_failing=True)
    ctx.deliver("scene", scene)
    state = planner_pb2.PlannerState(scenario=planner_pb2.SCENARIO_PLATOON, machine="platooning", state="FOLLOWING",
                                     time_in_state_s=2.5, graph_mermaid="stateDiagram-v2\n  JOINING --> FOLLOWING")
    state.recent_transitions.add(time_s=7.5, from_state="JOINING", to_state="FOLLOWING", event="joined",
                                 reason="gap reached", forced=False)
    ctx.deliver("planner/state", state)
    status = v2x_pb2.V2xStatus(packets_sent=120, packets_received=250)
    status.stations.add(station_id=4242, state=v2x_pb2.LINK_STATE_ACTIVE, message_rate_hz=25.0, reception_ratio=0.98,
                        expected_cam_rate_hz=25.0, trust=0.9, signed=True, verified=True, trusted=True, messages_received=250,
                        messages_signed=250, messages_verified=249, messages_trusted=249, signature_failures=1,
                        last_security_reason="")
    status.stations.add(station_id=99, state=v2x_pb2.LINK_STATE_LOST, trust=0.4)
    # Heard only as refused: signed by a signer whose root this vehicle does not trust.
    status.stations.add(station_id=666, state=v2x_pb2.LINK_STATE_LOST, signed=True, messages_signed=12,
                        messages_refused_by_security=12, messages_untrusted=12, last_security_reason="untrusted")
    status.rejected_by_reason["implausible_speed"] = 3
    ctx.deliver("v2x/status", status)
    actuation = actuation_pb2.ActuationStatus(mode=actuation_pb2.DRIVING_MODE_MANUAL,
                                              last_mode_change_reason="driver")
    actuation.availability.add(mode=actuation_pb2.DRIVING_MODE_COOPERATIVE, available=False,
                               unmet_condition="slow enough to engage")
    ctx.deliver("actuation/status", actuation)


@pytest.fixture
def feed():
    return feed_a_following_vehicle


# ----- a real `coopdrive run follow --realtime --gateway PORT` per test file ------------------
# Longer than any file's tests take on a loaded machine: the fixture stops the run when the file is done.
RUN_DURATION_S = 600
RUN_POLL_PERIOD_S = 0.5
RUN_REQUEST_TIMEOUT_S = 10.0
RUN_STOP_TIMEOUT_S = 10.0


class Run:
    def __init__(self, process: subprocess.Popen, port: int, log_path: Path):
        self.process = process
        self.port = port
        self.log_path = log_path
        self.http = httpx.Client(base_url=f"http://127.0.0.1:{port}", timeout=RUN_REQUEST_TIMEOUT_S)

    def poll_json(self, path: str, until, deadline_s: float, what: str) -> dict:
        """GETs `path` until `until(body)` holds; fails naming `what` and the last answer."""
        deadline = time.monotonic() + deadline_s
        last: object = "no answer yet"
        while time.monotonic() < deadline:
            if self.process.poll() is not None:
                log_tail = self.log_path.read_text().strip().splitlines()[-5:]
                pytest.fail(f"the run exited with {self.process.returncode} while waiting for {what}; "
                            f"its log ends: {log_tail}")
            try:
                body = self.http.get(path).json()
            except httpx.TransportError as error:  # the gateway is not listening yet
                last = repr(error)
            else:
                if until(body):
                    return body
                last = body
            time.sleep(RUN_POLL_PERIOD_S)
        pytest.fail(f"no {what} within {deadline_s} s; last answer: {last}")


def start_follow_run(log_path: Path) -> Run:
    """`coopdrive run follow --realtime --gateway PORT` on a free port, its output in `log_path`."""
    port = free_tcp_port()
    with open(log_path, "w") as output:
        process = subprocess.Popen(
            [sys.executable, "-m", "coopdrive.cli", "run", "follow", "--realtime", "--gateway", str(port),
             "--duration", str(RUN_DURATION_S)],
            stdin=subprocess.DEVNULL, stdout=output, stderr=subprocess.STDOUT, start_new_session=True)
    return Run(process, port, log_path)


def stop_follow_run(live: Run) -> None:
    live.http.close()
    if live.process.poll() is None:
        live.process.send_signal(signal.SIGTERM)
        try:
            live.process.wait(timeout=RUN_STOP_TIMEOUT_S)
        except subprocess.TimeoutExpired:
            live.process.kill()
            live.process.wait()


@pytest.fixture(scope="module")
def follow_run(tmp_path_factory):
    """One run for a test file's tests that only watch it (a file's tests run together, on one worker, within
    the run's duration); a test that stops a run starts its own."""
    live = start_follow_run(tmp_path_factory.mktemp("run") / "run.log")
    yield live
    stop_follow_run(live)


@pytest.fixture
def own_follow_run(tmp_path):
    live = start_follow_run(tmp_path / "run.log")
    yield live
    stop_follow_run(live)
