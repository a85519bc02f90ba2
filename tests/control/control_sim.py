"""Small deterministic simulations for the control tests: a platoon, a cruise run and a lane change.

Plant: first-order driveline lag tau a' + a = u(t - dead time), explicit Euler at 50 Hz; V2V acceleration
delayed by a few samples. No noise, so every run is repeatable.
"""

from __future__ import annotations

import math
import random
from collections import deque
from dataclasses import dataclass

from coopdrive.services.control.lateral import LateralController, LateralLaw
from coopdrive.services.control.longitudinal import CaccLaw, LongitudinalController, Spacing, Target
from coopdrive.services.control.profiles import CAR, VehicleProfile

DT_S = 0.02
STANDSTILL_M = 6.0
FOLLOWER_LAGS_S = (0.2, 0.25, 0.3, 0.35, 0.4, 0.45, 0.5)
CRUISE_FAST_MPS = 120 / 3.6


def wide_limits(profile: VehicleProfile) -> VehicleProfile:
    """Limits out of the way, for the linear string-stability run (the +-10 km/h sinusoid needs 3.5 m/s2)."""
    return profile.model_copy(update={
        "limits": profile.limits.model_copy(update={"max_accel_mps2": 10.0, "max_decel_mps2": 10.0,
                                                    "max_jerk_mps3": 100.0, "emergency_decel_mps2": 12.0}),
        "cruise": profile.cruise.model_copy(update={"reference_accel_mps2": 10.0, "reference_jerk_mps3": 100.0}),
    })


@dataclass
class PlatoonRun:
    speed_amplitudes_mps: list[float]
    min_gaps_m: list[float]
    final_gaps_m: list[float]
    final_time_gaps_s: list[float]
    modes: list[set[int]]
    emergency_steps: int

    @property
    def ratios(self) -> list[float]:
        a = self.speed_amplitudes_mps
        return [a[i + 1] / a[i] for i in range(len(a) - 1)]


def run_platoon(
    law: CaccLaw,
    time_gap_s: float,
    amplitude_kmh: float = 10.0,
    frequency_hz: float = 0.2,
    speed_mps: float = 80 / 3.6,
    duration_s: float = 30.0,
    measure_last_s: float = 10.0,
    comfort_limits: bool = False,
    v2v_lost_from_s: float | None = None,
    comm_delay_steps: int = 2,
    actuation_delay_steps: int = 2,
    brake_at_s: float | None = None,
    brake_decel_mps2: float = 5.0,
    driveline_jerk_mps3: float = math.inf,
    send_requests: bool = False,
    speed_noise_mps: float = 0.0,
) -> PlatoonRun:
    """Leader speed v0 + A sin(2 pi f t), or braking to standstill from brake_at_s; seven followers, each with its
    own lag, following its predecessor. send_requests adds each vehicle's requested acceleration to its V2V
    (iCLCM): the leader requests exactly what it does, a follower what its controller commanded.
    speed_noise_mps is the standard deviation of white noise on the predecessor speed a follower measures
    (seeded, so runs repeat)."""
    noise = random.Random(1)
    n = len(FOLLOWER_LAGS_S)
    base = CAR if comfort_limits else wide_limits(CAR)
    ctrls = [LongitudinalController(base.with_driveline(lag_s=lag), cacc_law=law) for lag in FOLLOWER_LAGS_S]
    amp = amplitude_kmh / 3.6
    w = 2 * math.pi * frequency_hz
    x = [0.0]
    for _ in range(n):
        x.append(x[-1] - (STANDSTILL_M + time_gap_s * speed_mps))
    v, a = [speed_mps] * (n + 1), [0.0] * (n + 1)
    commands = [deque([0.0] * (actuation_delay_steps + 1), maxlen=actuation_delay_steps + 1) for _ in range(n)]
    sent_accel = [deque([0.0] * (comm_delay_steps + 1), maxlen=comm_delay_steps + 1) for _ in range(n + 1)]
    sent_request = [deque([0.0] * (comm_delay_steps + 1), maxlen=comm_delay_steps + 1) for _ in range(n + 1)]
    steps, first = int(duration_s / DT_S), int((duration_s - measure_last_s) / DT_S)
    lo, hi = [math.inf] * (n + 1), [-math.inf] * (n + 1)
    min_gaps, modes, emergency, time_gaps = [math.inf] * n, [set() for _ in range(n)], 0, [0.0] * n
    for k in range(steps):
        t = k * DT_S
        lost = v2v_lost_from_s is not None and t >= v2v_lost_from_s
        for j in range(n + 1):
            sent_accel[j].append(a[j])
            sent_request[j].append(a[0] if j == 0 else commands[j - 1][-1])
        for i in range(n):
            gap = x[i] - x[i + 1]
            measured_speed_mps = v[i] + (noise.gauss(0.0, speed_noise_mps) if speed_noise_mps > 0 else 0.0)
            target = Target(object_id=i + 1, gap_m=gap, speed_mps=measured_speed_mps,
                            accel_mps2=None if lost else sent_accel[i][0],
                            v2v_age_s=None if lost else comm_delay_steps * DT_S,
                            intended_accel_mps2=sent_request[i][0] if send_requests and not lost else None)
            cmd = ctrls[i].step(t, v[i + 1], a[i + 1], [target], CRUISE_FAST_MPS, Spacing(STANDSTILL_M, time_gap_s))
            commands[i].append(cmd.accel_request_mps2)
            modes[i].add(cmd.mode)
            emergency += cmd.emergency_brake
            min_gaps[i] = min(min_gaps[i], gap)
            time_gaps[i] = cmd.time_gap_s
        if brake_at_s is not None and t + DT_S >= brake_at_s:
            a[0] = -brake_decel_mps2 if v[0] > 0 else 0.0
            v[0] = max(v[0] - brake_decel_mps2 * DT_S, 0.0)
        else:
            a[0] = amp * w * math.cos(w * (t + DT_S))
            v[0] = speed_mps + amp * math.sin(w * (t + DT_S))
        x[0] += v[0] * DT_S
        for i, lag in enumerate(FOLLOWER_LAGS_S):
            change = DT_S / lag * (commands[i][0] - a[i + 1])
            a[i + 1] += min(max(change, -driveline_jerk_mps3 * DT_S), driveline_jerk_mps3 * DT_S)
            v[i + 1] = max(v[i + 1] + a[i + 1] * DT_S, 0.0)
            x[i + 1] += v[i + 1] * DT_S
        if k >= first:
            for j in range(n + 1):
                lo[j], hi[j] = min(lo[j], v[j]), max(hi[j], v[j])
    return PlatoonRun(
        speed_amplitudes_mps=[(h - low) / 2 for h, low in zip(hi, lo)],
        min_gaps_m=min_gaps,
        final_gaps_m=[x[i] - x[i + 1] for i in range(n)],
        final_time_gaps_s=time_gaps,
        modes=modes,
        emergency_steps=emergency,
    )


def run_cruise(profile: VehicleProfile, desired_speed_mps: float, duration_s: float = 40.0) -> list[float]:
    """Standstill to desired speed; the plant feels rolling and aerodynamic resistance. Returns the speed trace."""
    ctrl = LongitudinalController(profile)
    lag = profile.engine_lag_s
    delay = deque([0.0] * 3, maxlen=3)
    v = drive = 0.0
    accel = 0.0
    trace = []
    for k in range(int(duration_s / DT_S)):
        cmd = ctrl.step(k * DT_S, v, accel, [], desired_speed_mps)
        delay.append(cmd.accel_request_mps2)
        drive += DT_S / lag * (delay[0] - drive)
        accel = drive - profile.resistance_accel_mps2(v)
        v = max(0.0, v + accel * DT_S)
        trace.append(v)
    return trace


@dataclass
class LaneChangeRun:
    times_s: list[float]
    offsets_m: list[float]
    lateral_accels_mps2: list[float]


def run_lane_change(
    law: LateralLaw,
    speed_mps: float,
    lane_width_m: float = 3.5,
    switch_at_s: float = 2.0,
    duration_s: float = 20.0,
    curvature_1pm: float = 0.0,
    steering_lag_s: float = 0.1,
) -> LaneChangeRun:
    """Kinematic bicycle (Heudiasyc eq. 5) in the lane frame; the target lane moves one lane left at switch_at_s.

    offsets_m is the offset to the target lane centre: about -lane_width after the switch, 0 when done.
    """
    ctrl = LateralController(CAR, law)
    wb = CAR.wheelbase_m
    y = heading = steer = 0.0
    run = LaneChangeRun([], [], [])
    for k in range(int(duration_s / DT_S)):
        t = k * DT_S
        offset = y - (lane_width_m if t >= switch_at_s else 0.0)
        cmd = ctrl.step(t, speed_mps, offset, heading, curvature_1pm)
        steer += DT_S / steering_lag_s * (cmd.steering_angle_rad - steer)
        station_rate = speed_mps * math.cos(heading) / (1 - curvature_1pm * y)
        y += speed_mps * math.sin(heading) * DT_S
        heading += (speed_mps * math.tan(steer) / wb - curvature_1pm * station_rate) * DT_S
        run.times_s.append(t)
        run.offsets_m.append(offset)
        run.lateral_accels_mps2.append(speed_mps**2 * math.tan(steer) / wb)
    return run
