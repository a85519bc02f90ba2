"""A follow run whose control service process is killed mid-run: actuation's watchdog stops the ego at its
configured deceleration, with the reason in its status, and the ego never hits the leader.

Started as run_scenario starts a run (hub bus, ServiceProcesses), because run_scenario has no hook to reach
ServiceProcesses.kill while the run goes on. Lockstep: the simulator drops the lost participant and continues.
"""

from __future__ import annotations

import threading
import time


from coopdrive.bus import Bus, BusConfig
from coopdrive.bus.keys import WORLD_ID
from coopdrive.launch.ports import free_tcp_port, loopback_endpoint
from coopdrive.launch.process_layout import ProcessLayout
from coopdrive.launch.processes import ServiceProcesses
from coopdrive.launch.run import RunOptions, build_specs, start_processes
from coopdrive.services.actuation.config import WatchdogConfig
from coopdrive.v1 import actuation_pb2

EGO = "ego"
RUN_DURATION_S = 20.0
KILL_AT_S = 8.0
RUN_TIMEOUT_S = 240.0
STOPPED_MPS = 0.2
# The stop ramps in at a bounded jerk and the vehicle model lags the command: judge the deceleration
# over the part of the stop after the ramp, within this tolerance of the configured rate.
DECEL_TOLERANCE_MPS2 = 0.6
SAFE_GAP_M = 2.0
# Simulated time that does not advance for this long: the run is stuck (fail instead of hanging).
STALL_S = 15.0


class LiveRun:
    """What the hub sees: ground truth (time, ego, leader), actuation statuses, the result."""

    def __init__(self):
        self.lock = threading.Lock()
        self.truth: list[tuple[float, object, object]] = []
        self.statuses: list[actuation_pb2.ActuationStatus] = []
        self.result = None
        self.finished = threading.Event()
        self.sim_time_s = 0.0

    def on_message(self, key: str, message) -> None:
        with self.lock:
            if key.endswith("world/clock"):
                self.sim_time_s = message.time_s
            elif key.endswith("world/ground_truth"):
                vehicles = {v.vehicle_id: v for v in message.vehicles}
                leader = min((v for v in message.vehicles if v.vehicle_id != EGO and v.station_m > vehicles[EGO].station_m),
                             key=lambda v: v.station_m, default=None)
                self.truth.append((message.header.sample_time_s, vehicles[EGO], leader, message.collisions))
                self.sim_time_s = max(self.sim_time_s, message.header.sample_time_s)
            elif key.endswith(f"{EGO}/actuation/status"):
                self.statuses.append(message)
            elif key.endswith("world/result"):
                self.result = message
                self.finished.set()


def run_with_control_killed(tmp_path) -> LiveRun:
    # Each service its own process, as on the vehicle: only control dies.
    options = RunOptions(duration_s=RUN_DURATION_S, processes=ProcessLayout.SERVICE)
    specs = build_specs(options, tmp_path)
    endpoint = loopback_endpoint(free_tcp_port())
    hub = Bus(BusConfig(listen=[endpoint]))
    live = LiveRun()
    hub.subscribe_key("coopdrive/**", live.on_message)
    processes = ServiceProcesses(endpoint, clock="sim", log_dir=tmp_path / "logs")
    killed = False
    try:
        start_processes(processes, specs, options)
        started_s = last_progress_s = time.monotonic()
        last_sim_s = -1.0
        while not live.finished.wait(0.05) and time.monotonic() - started_s < RUN_TIMEOUT_S:
            with live.lock:
                now_s = live.sim_time_s
            if now_s != last_sim_s:
                last_sim_s, last_progress_s = now_s, time.monotonic()
            assert time.monotonic() - last_progress_s < STALL_S, \
                f"simulated time stuck at {now_s:.2f} s (control killed: {killed})"
            if not killed and now_s >= KILL_AT_S:
                processes.kill(f"{EGO}/control")
                killed = True
            if f"{WORLD_ID}/sim" in processes.exited():
                live.finished.wait(1.0)
                break
    finally:
        processes.stop_all()
        hub.close()
    assert killed, f"the run never reached {KILL_AT_S} s (sim time {live.sim_time_s:.2f} s)"
    assert live.result is not None, "the simulator ended without a result"
    return live


def test_the_watchdog_stops_the_ego_at_its_deceleration_when_the_control_process_dies(tmp_path):
    live = run_with_control_killed(tmp_path)
    decel_mps2 = WatchdogConfig().stop_decel_mps2
    after = [(t, ego, leader, collisions) for t, ego, leader, collisions in live.truth if t >= KILL_AT_S]
    assert after, "no ground truth after the kill"
    speed_at_kill = after[0][1].speed_mps
    assert speed_at_kill > 1.0, f"the ego was not moving when control died ({speed_at_kill:.2f} m/s)"

    stop_times = [t for t, ego, _, _ in after if ego.speed_mps <= STOPPED_MPS]
    assert stop_times, f"the ego never stopped: last speed {after[-1][1].speed_mps:.2f} m/s"
    stop_s = stop_times[0] - KILL_AT_S
    mean_decel_mps2 = speed_at_kill / stop_s
    # The whole stop, including the jerk-limited ramp-in and the timeout before it, averages a bit less than
    # the configured rate; it must never be harsher than it (no estop) nor much gentler.
    assert decel_mps2 - 2 * DECEL_TOLERANCE_MPS2 < mean_decel_mps2 <= decel_mps2 + DECEL_TOLERANCE_MPS2, \
        f"stopped from {speed_at_kill:.2f} m/s in {stop_s:.2f} s: {mean_decel_mps2:.2f} m/s2 vs {decel_mps2}"
    peak_decel_mps2 = -min(ego.accel_mps2 for _, ego, _, _ in after)
    assert abs(peak_decel_mps2 - decel_mps2) < DECEL_TOLERANCE_MPS2, \
        f"peak deceleration {peak_decel_mps2:.2f} m/s2 vs the configured {decel_mps2}"

    gaps_m = [leader.station_m - ego.station_m - (leader.length_m + ego.length_m) / 2
              for _, ego, leader, _ in after if leader is not None]
    assert min(gaps_m) > SAFE_GAP_M, f"gap fell to {min(gaps_m):.2f} m"
    assert live.truth[-1][3] == 0 and live.result.metrics["collisions"] == 0

    stop_statuses = [s for s in live.statuses if s.header.sample_time_s >= KILL_AT_S
                     and s.mode == actuation_pb2.DRIVING_MODE_SAFE_STOP]
    assert stop_statuses, "actuation never reported a safe stop"
    # Whichever the actuator notices first: control's liveliness token gone, or its last command too old.
    reason = stop_statuses[-1].last_mode_change_reason
    assert "control not alive" in reason or "control command too old" in reason, reason
    assert stop_statuses[-1].hazard_lights
    assert live.result.metrics["participants_lost"] >= 1
