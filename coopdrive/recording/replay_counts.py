"""What a replayed service counted, in words: per input, how many it received, used, ignored and refused (by reason),
and a warning for a recorded input it ignored in full (a car's CAN frames replayed without the car's adapter).

The counters are the service's own (the ones its diagnostics carry live); their names say what they count:
`accepted_<kind>` and `gated_<kind>` are a filter's updates used and beyond its chi-square gate (refused; but a
receiver alone's speed and course beyond it are fused with their noise inflated, and count as both),
`can_frames_received` / `can_frames_ignored` / `can_rejected_<reason>` the vehicle bus reader's frames (see
coopdrive/can/bus_reader.py). Any other counter is listed under its own name.
"""

from __future__ import annotations

from collections.abc import Mapping

USED_PREFIX = "accepted_"
GATED_PREFIX = "gated_"
CAN_USED = "can_frames_received"
CAN_IGNORED = "can_frames_ignored"
CAN_IDS_IGNORED = "can_ids_ignored"
CAN_REJECTED_PREFIX = "can_rejected_"
CAN_ERROR_FRAMES = "can_error_frames"
CAN_COUNTERS = (CAN_USED, CAN_IGNORED, CAN_IDS_IGNORED, CAN_ERROR_FRAMES)
# A value the service estimated, `estimated_<what>`, and its one-sigma std, `estimated_<what>_std`.
ESTIMATED_PREFIX = "estimated_"
STD_SUFFIX = "_std"


def _label(kind: str) -> str:
    return kind.replace("_", " ")


def _count(value: float) -> str:
    return f"{value:g}"


def _gated_lines(counters: Mapping[str, float]) -> list[str]:
    kinds = sorted({name.removeprefix(prefix) for name in counters for prefix in (USED_PREFIX, GATED_PREFIX)
                    if name.startswith(prefix)})
    lines = []
    for kind in kinds:
        used, refused = counters.get(USED_PREFIX + kind, 0), counters.get(GATED_PREFIX + kind, 0)
        lines.append(f"{_label(kind)} updates: {_count(used)} used, {_count(refused)} beyond the gate")
    return lines


def _can_line(counters: Mapping[str, float]) -> list[str]:
    rejected = {name.removeprefix(CAN_REJECTED_PREFIX): n for name, n in counters.items()
                if name.startswith(CAN_REJECTED_PREFIX)}
    if CAN_USED not in counters and CAN_IGNORED not in counters and not rejected:
        return []
    used, ignored = counters.get(CAN_USED, 0), counters.get(CAN_IGNORED, 0)
    errors = counters.get(CAN_ERROR_FRAMES, 0)
    received = used + ignored + errors + sum(rejected.values())
    reasons = ", ".join(f"{_count(n)} {_label(reason)}" for reason, n in sorted(rejected.items())) or "none"
    return [f"CAN frames: {_count(received)} received, {_count(used)} used, {_count(ignored)} ignored "
            f"({_count(counters.get(CAN_IDS_IGNORED, 0))} ids the adapter does not use), {_count(errors)} error "
            f"frames, refused: {reasons}"]


def _estimated_lines(counters: Mapping[str, float]) -> list[str]:
    names = sorted(name for name in counters if name.startswith(ESTIMATED_PREFIX) and not name.endswith(STD_SUFFIX))
    lines = []
    for name in names:
        std = counters.get(name + STD_SUFFIX)
        spread = "" if std is None else f" +- {std:.2g} (1 sigma)"
        lines.append(f"{_label(name)}: {counters[name]:.5g}{spread}")
    return lines


def counter_lines(counters: Mapping[str, float]) -> list[str]:
    """One line per input the counters describe, one per value the service estimated (with its std), then every
    other counter as `name value`."""
    lines = _gated_lines(counters) + _can_line(counters) + _estimated_lines(counters)
    described = {name for name in counters
                 if name.startswith((USED_PREFIX, GATED_PREFIX, CAN_REJECTED_PREFIX, ESTIMATED_PREFIX))}
    others = sorted(name for name in counters if name not in described and name not in CAN_COUNTERS)
    lines += [f"{name} {_count(counters[name])}" for name in others]
    return lines


def replay_warnings(service_name: str, counters: Mapping[str, float]) -> list[str]:
    """Recorded inputs the service could use but ignored, every one of them."""
    ignored = counters.get(CAN_IGNORED, 0)
    decoded = counters.get(CAN_USED, 0) + sum(n for name, n in counters.items() if name.startswith(CAN_REJECTED_PREFIX))
    if ignored and not decoded:
        return [f"{service_name} ignored all {_count(ignored)} CAN frames ({_count(counters.get(CAN_IDS_IGNORED, 0))} "
                f"ids): its vehicle CAN adapter uses none of them; give the car's with --set vehicle_can=FILE"]
    return []
