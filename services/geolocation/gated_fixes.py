"""Fixes the gate refused, kept to decide whether the filter or the receiver is wrong.

A filter that drifted (dead reckoning through an outage, a float solution turning fixed) sees the fixes move
smoothly against it, each about where the last one was: resetting to them after a while is right. A receiver in
multipath jumps: its fixes step by metres from one to the next, and a reset would only move the estimate onto one
of the jumps. So the refused fixes count towards a reset only since the last such step.
"""
from __future__ import annotations

import math
from dataclasses import dataclass

# Consecutive fixes agree when they are within this many of their reported sigmas of each other (or the floor in
# GeolocatorConfig.gnss_reset_consistency_m, whichever is larger).
CONSISTENCY_SIGMAS = 4.0


@dataclass(frozen=True)
class GatedFixes:
    # Since when the refused fixes have moved smoothly.
    since_s: float
    # The newest refused fix's offset from the estimate (rear-axle east, north).
    offset_m: tuple[float, float]

    def with_fix(self, time_s: float, offset_m: tuple[float, float], fix_std_m: float,
                 floor_m: float) -> GatedFixes:
        """The next refused fix: a step beyond the tolerance from the last one starts the count again."""
        tolerance_m = max(floor_m, CONSISTENCY_SIGMAS * fix_std_m)
        step_m = math.hypot(offset_m[0] - self.offset_m[0], offset_m[1] - self.offset_m[1])
        return GatedFixes(self.since_s if step_m <= tolerance_m else time_s, offset_m)
