"""RuntimeEvent: the kinds of event a service's worker takes from its queue, shared by the runner and the clock
master (and by tests that drive either)."""

from __future__ import annotations

from enum import Enum, auto


class RuntimeEvent(Enum):
    # A message of a subscribed topic (payload: Envelope).
    DATA = auto()
    # The simulator's clock for a step (payload: SimClock).
    CLOCK = auto()
    # A step marker (payload: participant, step, next_step, sequences).
    DONE = auto()
    # A liveliness token came or went (payload: participant, alive).
    ALIVE = auto()
    STOP = auto()
    # A function handed over by call_soon (payload: the function).
    CALL = auto()
