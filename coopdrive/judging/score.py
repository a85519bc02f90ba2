"""Scores a run from its messages with the simulator's judge (services/sim/metrics.py).

Everything is computed from the recorded GroundTruth samples (10 Hz), so scoring a
recording afterwards and scoring the same messages live give the same numbers.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from pathlib import Path

import numpy as np

from coopdrive.judging.counts import COUNT_METRICS
from coopdrive.judging.localisation import localisation_metrics
from coopdrive.judging.run_messages import RunMessages
from coopdrive.judging.tracking import tracking_metrics
from coopdrive.services.sim import metrics as judge_metrics
from coopdrive.services.sim.truth_series import TruthSeries
from coopdrive.v2x.reasons import RejectReason
from coopdrive.v2x.security_verdict import UNTRUSTED_REASONS
from coopdrive.v1 import ego_pb2, v2x_pb2

# A scene object is taken for the true vehicle whose rear bumper centre is this close.
ASSOCIATION_GATE_M = 3.0


class ScoreError(ValueError):
    """A recording that cannot be scored; str() says why."""


@dataclass(frozen=True)
class JudgingParameters:
    """What the judge needs beyond the truth; defaults are the follow scenario's (eq. 4 Heudiasyc r, h)."""

    safety_radius_m: float = judge_metrics.DEFAULT_SAFETY_RADIUS_M
    standstill_m: float = judge_metrics.DEFAULT_STANDSTILL_M
    headway_s: float = judge_metrics.DEFAULT_HEADWAY_S
    string_start_s: float = 0.0
    string_frequency_hz: float | None = None
    string_end_s: float = math.inf
    # Leader first, as the scenario declares it (empty: it declares none, and no platoon is judged); None, for a
    # recording of no known scenario: the vehicles of the leading lane ordered along it at the first sample.
    platoon: tuple[str, ...] | None = None


def truth_series(messages: RunMessages) -> TruthSeries:
    truth = messages.sorted_truth()
    if not truth:
        raise ScoreError("no world/ground_truth messages to score")
    return TruthSeries.from_ground_truth(truth)


def _position_estimates(series: TruthSeries, messages: RunMessages) -> dict[str, tuple[np.ndarray, np.ndarray]]:
    estimates = {}
    for vehicle_id, states in messages.ego_states.items():
        # An estimate that says it is lost (before the first fix) claims no position to be judged on.
        states = [s for s in states if s.mode != ego_pb2.LOCALISATION_MODE_LOST]
        if vehicle_id not in series.values or not states:
            continue
        times = np.array([s.header.sample_time_s for s in states])
        xy = np.array([[s.x_m, s.y_m] for s in states])
        estimates[vehicle_id] = (times, xy)
    return estimates


def v2x_metrics(messages: RunMessages) -> dict[str, float]:
    """V2X figures from each vehicle's last v2x/status: packet totals, the worst link's reception and delay."""
    statuses = list(messages.v2x_status.values())
    if not statuses:
        return {}
    # Links of stations heard at all: one only ever refused by the security mode has no link quality to judge
    # (v2v_listeners says who was not heard).
    stations = [station for status in statuses for station in status.stations if station.messages_received > 0]
    figures = {"v2x_packets_sent": float(sum(s.packets_sent for s in statuses)),
               "v2x_packets_received": float(sum(s.packets_received for s in statuses)),
               "v2x_packets_rejected": float(sum(sum(s.rejected_by_reason.values()) for s in statuses))}
    if stations:
        figures.update(pair_reception(stations))
        figures["v2x_update_delay_p95_max_s"] = max(s.update_delay_p95_s for s in stations)
    rejected = [(reason, count) for status in statuses for reason, count in status.rejected_by_reason.items()]
    figures["v2x_rejected_untrusted"] = float(sum(count for reason, count in rejected if reason in UNTRUSTED_REASONS))
    figures["v2x_rejected_certificate_expired"] = float(
        sum(count for reason, count in rejected if reason == RejectReason.CERTIFICATE_EXPIRED.value))
    figures.update(v2v_listeners(messages))
    return figures


def pair_reception(stations: list[v2x_pb2.StationLinkStats]) -> dict[str, float]:
    """Reception ratio of each (sender, receiver) pair while both are sending: periodic messages received over
    the slots they close, since the sender was first heard (a status without those totals, from before they
    existed, gives its windowed ratio). The worst pair and the mean over pairs."""
    ratios = [s.periodic_received_total / s.periodic_expected_total if s.periodic_expected_total
              else s.reception_ratio for s in stations]
    return {"v2x_reception_ratio_min": min(ratios), "v2x_reception_ratio_mean": float(np.mean(ratios)),
            "v2x_reception_pairs": float(len(ratios))}


def v2v_listeners(messages: RunMessages) -> dict[str, float]:
    """Per stack vehicle, how many other stacks accepted V2X messages from it (v2v_listeners_<vehicle>), and
    how many stacks none did (v2v_unheard_stacks): a stack whose packets all others drop, e.g. signed under a
    root nobody trusts, is to them a vehicle without V2V."""
    stacks = messages.v2x_status
    if len(stacks) < 2 or not messages.truth:
        return {}
    station_of = {vehicle.vehicle_id: vehicle.station_id for truth in messages.truth for vehicle in truth.vehicles}
    figures = {}
    for vehicle_id in sorted(stacks):
        station_id = station_of.get(vehicle_id)
        figures[f"v2v_listeners_{vehicle_id}"] = float(sum(
            any(s.station_id == station_id and s.messages_received > 0 for s in status.stations)
            for listener, status in stacks.items() if listener != vehicle_id))
    figures["v2v_unheard_stacks"] = float(sum(count == 0 for count in figures.values()))
    return figures


def _clean(metrics: dict[str, float]) -> dict[str, float | int | None]:
    """JSON-ready: counts as int, non-finite values (nothing to measure) as None."""
    cleaned: dict[str, float | int | None] = {}
    for key, value in sorted(metrics.items()):
        if value is None or not math.isfinite(value):
            cleaned[key] = None
        elif key in COUNT_METRICS:
            cleaned[key] = int(value)
        else:
            cleaned[key] = float(value)
    return cleaned


def score_series(series: TruthSeries, parameters: JudgingParameters = JudgingParameters(),
                 messages: RunMessages | None = None) -> dict:
    """The judge's metrics of a truth series; the stacks' ego states and scenes in `messages` add
    position_rmse_m, and their scenes the tracking figures of coopdrive.judging.tracking."""
    messages = messages if messages is not None else RunMessages()
    # A run of fewer stacks than the scenario has leaves the platoon's tail out of the world.
    platoon = (judge_metrics.leading_lane_platoon(series) if parameters.platoon is None
               else [v for v in parameters.platoon if v in series.values])
    scored = judge_metrics.judge(
        series, platoon=platoon,
        safety_radius_m=parameters.safety_radius_m, standstill_m=parameters.standstill_m,
        headway_s=parameters.headway_s, string_start_s=parameters.string_start_s,
        string_frequency_hz=parameters.string_frequency_hz, string_end_s=parameters.string_end_s,
        position_estimates=_position_estimates(series, messages))
    if messages.ego_states:
        scored.update(localisation_metrics(series, messages, scored.get("position_rmse_m", math.nan)))
    if messages.scenes:
        scored.update(tracking_metrics(series, messages, ASSOCIATION_GATE_M))
    scored.update(v2x_metrics(messages))
    scored["truth_samples"] = float(series.time_s.size)
    scored["truth_duration_s"] = float(series.time_s[-1] - series.time_s[0])
    scored.update(truth_coverage(series.time_s))
    return _clean(scored)


def truth_coverage(time_s: np.ndarray) -> dict[str, float]:
    """How much of the truth the recording holds: samples missing between the first and the last at the truth's
    own period (the median interval), and the longest interval. Every other figure is only as good as this: the
    judge interpolates across a gap as if the vehicles had moved in a straight line at constant speed."""
    if time_s.size < 2:
        return {}
    intervals = np.diff(time_s)
    period_s = float(np.median(intervals))
    expected = int(round((time_s[-1] - time_s[0]) / period_s)) + 1 if period_s > 0 else time_s.size
    return {"truth_missing_samples": float(max(0, expected - time_s.size)),
            "truth_longest_gap_s": float(intervals.max())}


def score_messages(messages: RunMessages, parameters: JudgingParameters = JudgingParameters()) -> dict:
    return score_series(truth_series(messages), parameters, messages)


def score_recording(path: str | Path, parameters: JudgingParameters = JudgingParameters()) -> dict:
    """The judge's metrics of an MCAP recording, snake_case keys with units (see score_messages)."""
    return score_messages(RunMessages.from_recording(path), parameters)
