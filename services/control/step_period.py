"""A controller's step period from the times of its calls, for both the longitudinal and the lateral controller."""

from __future__ import annotations

# The control period: the step taken for a controller's first call, and for a call after a break.
DEFAULT_DT_S = 0.02
# A gap in the calls longer than this, or time going backwards, is a break: the controller starts again from the
# measured state.
MAX_DT_S = 0.5


def step_period_s(last_time_s: float | None, time_s: float) -> tuple[float, bool]:
    """The period since the last call, and whether the calls broke off since it (then the period is DEFAULT_DT_S,
    as for the first call)."""
    if last_time_s is None:
        return DEFAULT_DT_S, False
    dt_s = time_s - last_time_s
    if dt_s <= 0 or dt_s > MAX_DT_S:
        return DEFAULT_DT_S, True
    return dt_s, False
