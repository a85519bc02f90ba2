"""Trust in each V2V station, in [0, 1].

Chalmers 4.3.1: V2V quality "might range from excellent to worthless" depending on the sender, so
trust is kept per station. It drops fast (drop_per_s) while a station's claims disagree with our own
ranging or fail plausibility, drops at once by ghost_penalty when it claims a spot our LiDAR and
radar see as free, and climbs back slowly (raise_per_s) while it agrees. Security counts too (the v2x
service's verdicts, `on_security`): trust drops while a station's packets fail (invalid signatures, refused by
the security mode), and never rises for a station whose signer does not chain to a root we trust.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

from .config import TrustConfig
from .measurement import V2vObservation

# Interval credited to a station's first message, before there is a previous one to measure from.
_FIRST_STEP_S = 0.1


@dataclass
class StationState:
    trust: float
    last_time_s: float | None = None
    last_observation: V2vObservation | None = None
    free_space_hits: int = 0
    ghost: bool = False
    disagreements: int = 0
    implausible: int = 0
    # The v2x service's cumulative count of this station's failed packets, when it last reported it.
    security_failures: int = 0
    last_security_s: float | None = None
    security_failing: bool = False
    untrusted_signer: bool = False


class V2vTrust:
    def __init__(self, config: TrustConfig) -> None:
        self._config = config
        self._stations: dict[int, StationState] = {}

    def state(self, station_id: int) -> StationState:
        if station_id not in self._stations:
            self._stations[station_id] = StationState(trust=self._config.initial)
        return self._stations[station_id]

    def trust(self, station_id: int | None) -> float:
        """Trust of a station; 1 for objects without a station (our own sensors)."""
        if station_id is None:
            return 1.0
        return self.state(station_id).trust

    def trusted(self, station_id: int) -> bool:
        state = self.state(station_id)
        return not state.ghost and state.trust >= self._config.min_trusted

    def is_ghost(self, station_id: int | None) -> bool:
        return station_id is not None and self.state(station_id).ghost

    def implausibility(self, obs: V2vObservation) -> str | None:
        """Why an observation cannot be true on its own, or None."""
        cfg = self._config
        if not 0.0 <= obs.speed_mps <= cfg.max_speed_mps:
            return f"speed {obs.speed_mps:.1f} m/s outside [0, {cfg.max_speed_mps}]"
        if abs(obs.accel_mps2) > cfg.max_abs_accel_mps2:
            return f"acceleration {obs.accel_mps2:.1f} m/s^2 beyond {cfg.max_abs_accel_mps2}"
        if obs.length_m > cfg.max_length_m:
            return f"length {obs.length_m:.1f} m beyond {cfg.max_length_m}"
        previous = self.state(obs.station_id).last_observation
        if previous is not None and obs.sample_time_s > previous.sample_time_s:
            dt = obs.sample_time_s - previous.sample_time_s
            moved = math.hypot(obs.x_m - previous.x_m, obs.y_m - previous.y_m)
            explained = max(obs.speed_mps, previous.speed_mps) * dt + cfg.jump_tolerance_m
            if moved > explained:
                return f"jumped {moved:.1f} m in {dt:.2f} s"
        return None

    def observe(self, obs: V2vObservation, disagreement_m: float | None, plausible: bool) -> float:
        """Update trust for one message. disagreement_m: distance to our own fix, None if not seen."""
        cfg = self._config
        state = self.state(obs.station_id)
        if state.last_time_s is None:
            step = _FIRST_STEP_S
        else:
            step = min(cfg.max_step_s, max(0.0, obs.sample_time_s - state.last_time_s))
        if not plausible:
            state.implausible += 1
            state.trust -= cfg.drop_per_s * step
        elif disagreement_m is not None and disagreement_m > cfg.agree_m:
            state.disagreements += 1
            state.trust -= cfg.drop_per_s * step
        elif disagreement_m is not None:
            # An untrusted signer may agree with our sensors: it still earns nothing.
            if not state.untrusted_signer:
                state.trust += cfg.raise_per_s * step
            # Our own sensors see it where it says it is: whatever free-space hits came before were wrong.
            state.free_space_hits = 0
            state.ghost = False
        state.trust = min(1.0, max(0.0, state.trust))
        if state.last_time_s is None or obs.sample_time_s >= state.last_time_s:
            state.last_time_s = obs.sample_time_s
            state.last_observation = obs
        return state.trust

    def on_security(self, station_id: int, failures: int, untrusted_signer: bool, time_s: float) -> float:
        """The v2x service's security report on a station: `failures`, its packets so far whose signature was
        invalid or that the security mode refused. Trust drops (drop_per_s) over each interval with new ones."""
        cfg = self._config
        state = self.state(station_id)
        if state.last_security_s is None:
            step = _FIRST_STEP_S
        else:
            step = min(cfg.max_step_s, max(0.0, time_s - state.last_security_s))
        state.security_failing = failures > state.security_failures
        state.security_failures = max(failures, state.security_failures)
        state.last_security_s = max(time_s, state.last_security_s or time_s)
        state.untrusted_signer = untrusted_signer
        if state.security_failing:
            state.trust = max(0.0, state.trust - cfg.drop_per_s * step)
        return state.trust

    def free_space_contradiction(self, station_id: int) -> None:
        """The station claims a spot that our LiDAR and radar see as empty."""
        cfg = self._config
        state = self.state(station_id)
        state.free_space_hits += 1
        state.trust = max(0.0, state.trust - cfg.ghost_penalty)
        if state.free_space_hits >= cfg.ghost_hits:
            state.ghost = True
            state.trust = 0.0

    def stations(self) -> dict[int, StationState]:
        return dict(self._stations)
