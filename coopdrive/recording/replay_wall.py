"""Replay of a recording without a lockstep clock: a vehicle's (`coopdrive record` on the wall clock) or an import.

The inputs are handed over in arrival order (their MCAP log times, which `coopdrive record` takes on arrival and
`coopdrive import` from the logs' own times), the service's clock reading each one's arrival time as it is
handled. Between two inputs the clock stops at every time a time trigger is due, so periodic outputs come at
their scheduled times, as they would live with a service that is never late. The schedule starts with the
service's first recorded output when there is one (live, the triggers' phase was set when it started, before
the recording may have), else with the first input.
"""

from __future__ import annotations

import logging

from coopdrive.bus import Envelope, KeyLayout
from coopdrive.bus.publish_spool import NANOSECONDS

log = logging.getLogger(__name__)

QUIET_LIMIT_S = 10.0


def run_wall_clock(ctx, inputs, recorded_outputs, layout: KeyLayout) -> int:
    """Feeds ctx (a ReplayContext) the inputs; returns how many were handled."""
    start_s = inputs[0].log_time_ns / NANOSECONDS
    if recorded_outputs:
        start_s = min(start_s, min(message.header.sent_time_s for _, message, _ in recorded_outputs))
    end_s = max(inputs[-1].log_time_ns / NANOSECONDS,
                max((message.header.sent_time_s for _, message, _ in recorded_outputs), default=start_s))
    _run_triggers(ctx, start_s)
    last_s = start_s
    for item in inputs:
        time_s = item.log_time_ns / NANOSECONDS
        _advance_to(ctx, min(time_s, last_s + QUIET_LIMIT_S))
        if time_s > last_s + QUIET_LIMIT_S:
            ctx.skipped_s += time_s - last_s - QUIET_LIMIT_S
            _run_triggers(ctx, time_s)  # the triggers skip the periods they missed (timers.py)
        last_s = time_s
        ctx.clock.set(time_s)
        vehicle, topic = layout.split(item.topic)
        try:
            ctx.dispatch(Envelope(vehicle, topic, item.message))
        except Exception:  # as live: one bad input must not end the replay; counted and reported
            ctx.handler_errors += 1
            if ctx.handler_errors == 1:
                log.exception("handler for %s failed", item.topic)
    _advance_to(ctx, min(end_s, last_s + QUIET_LIMIT_S))
    return len(inputs)


def _advance_to(ctx, time_s: float) -> None:
    """Runs every trigger due up to time_s, each at the time it is due."""
    while (due_s := ctx.triggers.next_due_s()) is not None and due_s <= time_s:
        _run_triggers(ctx, due_s)


def _run_triggers(ctx, time_s: float) -> None:
    ctx.clock.set(time_s)
    ctx.triggers.run_due(time_s)
