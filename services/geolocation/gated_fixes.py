"""Fixes the gate refused, kept to decide whether the filter or the receiver is wrong.

A filter that drifted (dead reckoning through an outage) sees the returning fixes all off by about the same
offset: resetting to them is right. A receiver in multipath jumps around: its fixes disagree with each other as
much as with the filter, and a reset would only move the estimate onto one of the jumps.
"""
from __future__ import annotations

import math
from dataclasses import dataclass

# Fixes agree when they lie within this many of their reported sigmas of the newest one (or the floor in
# GeolocatorConfig.gnss_reset_consistency_m, whichever is larger).
CONSISTENCY_SIGMAS = 4.0


@dataclass(frozen=True)
class GatedFixes:
    since_s: float
    # Each refused fix's offset from the estimate (rear-axle east, north).
    offsets_m: tuple[tuple[float, float], ...]

    def with_fix(self, offset_m: tuple[float, float]) -> GatedFixes:
        return GatedFixes(self.since_s, self.offsets_m + (offset_m,))

    def consistent(self, fix_std_m: float, floor_m: float) -> bool:
        """Whether every refused fix is within the tolerance of the newest: one offset, not jumps."""
        tolerance_m = max(floor_m, CONSISTENCY_SIGMAS * fix_std_m)
        newest_east, newest_north = self.offsets_m[-1]
        return all(math.hypot(east - newest_east, north - newest_north) <= tolerance_m
                   for east, north in self.offsets_m)
