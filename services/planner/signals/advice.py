"""What to do at a signalised stop line, from the phases of the ego's signal group (a pure function).

Stop on red; on amber stop when the stop line is beyond the stopping distance v t_r + v^2 / (2 a) at the
comfort deceleration (ITE's amber-interval kinematics), else proceed: the dilemma zone, which an amber timed for
that deceleration lets a vehicle clear; but where the SPaT says the amber ends before the ego would reach the line,
stop all the same: never enter on red. GLOSA (green light optimal speed advisory): when a green the ego could not
reach at the road's limit (nor in the amber after it) comes later, arrive at its start (plus a margin) at the constant speed d / (t_green - t),
no slower than a minimum; otherwise stop as without it.
"""

from __future__ import annotations

import enum
from dataclasses import dataclass

from ..config import SignalConfig
from .phases import GroupTiming, Light


class Advice(enum.Enum):
    GO = enum.auto()
    GLOSA = enum.auto()
    STOP = enum.auto()
    # Amber too close to stop comfortably: go on through.
    PROCEED = enum.auto()
    # A phase that gives no rule (dark, unavailable, flashing).
    UNKNOWN = enum.auto()


@dataclass(frozen=True)
class Approach:
    """The ego's approach to the stop line at one instant."""

    now_s: float
    to_stop_line_m: float
    speed_mps: float
    # The most the road (the scenario's request) allows.
    limit_mps: float


@dataclass(frozen=True)
class Advised:
    advice: Advice
    # GLOSA's speed; else the limit.
    speed_mps: float


def stopping_distance_m(speed_mps: float, config: SignalConfig) -> float:
    return speed_mps * config.reaction_time_s + speed_mps ** 2 / (2.0 * config.comfort_decel_mps2)


def advise(timing: GroupTiming, approach: Approach, config: SignalConfig, glosa: bool) -> Advised:
    current = timing.current
    light = current.light if current is not None else Light.UNKNOWN
    limit = approach.limit_mps
    later_green = _later_green_speed_mps(timing, approach, config) if glosa else None
    if light is Light.UNKNOWN:
        return Advised(Advice.UNKNOWN, limit)
    if light is Light.GO:
        until_s = _passable_until_s(timing, approach.now_s, config)
        lasts = until_s is None or limit <= 0.0 or until_s > approach.now_s + approach.to_stop_line_m / limit
        if lasts or later_green is None:
            return Advised(Advice.GO, limit)
        return Advised(Advice.GLOSA, later_green)
    if light is Light.AMBER and approach.to_stop_line_m < stopping_distance_m(approach.speed_mps, config) \
            and not _red_before_the_line(current.earliest_end_s, approach):
        return Advised(Advice.PROCEED, limit)
    if later_green is not None:
        return Advised(Advice.GLOSA, later_green)
    return Advised(Advice.STOP, limit)


def _red_before_the_line(amber_end_s: float | None, approach: Approach) -> bool:
    """At its speed the ego would reach the line after the amber's soonest end: proceeding would enter on red, so it
    stops, harder than comfort (a shorter amber than ITE's, or SPaT that says so)."""
    if amber_end_s is None:
        return False
    return approach.speed_mps <= 0.0 or approach.now_s + approach.to_stop_line_m / approach.speed_mps > amber_end_s


def _passable_until_s(timing: GroupTiming, now_s: float, config: SignalConfig) -> float | None:
    """Until when the current green lets the ego through: its end, or where amber follows, the amber's end less
    the GLOSA margin (the amber decision will proceed then: the line lies within the stopping distance); None
    when the green's end is unknown."""
    windows = timing.windows(now_s)
    until_s = windows[0][2]
    if until_s is not None and len(windows) > 1 and windows[1][0] is Light.AMBER and windows[1][2] is not None:
        until_s = max(until_s, windows[1][2] - config.glosa_margin_s)
    return until_s


def _later_green_speed_mps(timing: GroupTiming, approach: Approach, config: SignalConfig) -> float | None:
    """The constant speed that arrives at the first green after the current phase that can be reached between the
    limit and the minimum speed, or None. A green the SPaT of a moment ago said starts by now (the SPATEM saying it
    has not come yet) counts from its start."""
    now_s, distance_m = approach.now_s, approach.to_stop_line_m
    if distance_m <= 0.0 or approach.limit_mps < config.glosa_min_speed_mps:
        return None
    earliest_s = now_s + distance_m / approach.limit_mps
    latest_s = now_s + distance_m / config.glosa_min_speed_mps
    for light, start_s, end_s in timing.windows(now_s)[1:]:
        if light is not Light.GO:
            continue
        arrive_s = max(earliest_s, start_s + config.glosa_margin_s)
        if arrive_s > latest_s:
            return None
        if end_s is None or arrive_s < end_s:
            return min(distance_m / (arrive_s - now_s), approach.limit_mps)
    return None
