"""The roadside unit: starts and ends the scenario (iCLCM), announces road works (DENM), and at a signalised
intersection sends its map and signal states (MAPEM, SPATEM: signal_rsu.py)."""
from __future__ import annotations

import enum
import math
from typing import Sequence

from pydantic import BaseModel, ConfigDict, Field

from coopdrive.services.sim.participants import IntentKind, MessageIntent, RateGate
from coopdrive.services.sim.signal_rsu import SignalBroadcaster

DEFAULT_RSU_RATE_HZ = 25.0
# DENM cause code of road works (ETSI EN 302 637-3).
ROADWORKS_CAUSE = 3
# The longest validity a DENM can state (ETSI EN 302 637-3 ValidityDuration).
MAX_DENM_VALIDITY_S = 86400.0


class RsuEventKind(enum.Enum):
    START_PLATOON = "start_platoon"
    ROADWORKS = "roadworks"
    END_OF_SCENARIO = "end_of_scenario"


class RsuEvent(BaseModel):
    """From time_s to until_s the unit repeats this announcement at its rate."""

    model_config = ConfigDict(extra="forbid", frozen=True)

    kind: RsuEventKind
    time_s: float = Field(ge=0)
    until_s: float = math.inf
    # start_platoon: which platoon starts (0 = A at 80 km/h, 1 = B at 60 km/h).
    platoon: int = 0
    # roadworks: where, and which lane is closed.
    x_m: float = 0.0
    y_m: float = 0.0
    closed_lane: int = 1
    length_m: float = Field(default=300.0, gt=0)


class RoadsideUnit:
    def __init__(self, unit_id: str, station_id: int, x_m: float, y_m: float, events: Sequence[RsuEvent],
                 rate_hz: float = DEFAULT_RSU_RATE_HZ, signals: SignalBroadcaster | None = None) -> None:
        self.unit_id = unit_id
        self.station_id = station_id
        self.x_m = x_m
        self.y_m = y_m
        self.events = list(events)
        self._gate = RateGate(rate_hz)
        self.signals = signals
        self.silent = False

    def active_events(self, now_s: float) -> list[RsuEvent]:
        return [e for e in self.events if e.time_s <= now_s < e.until_s]

    def messages_due(self, now_s: float) -> list[MessageIntent]:
        if self.silent:
            return []
        intents = [] if self.signals is None else self.signals.messages_due(now_s, self.unit_id, self.x_m, self.y_m)
        if not self._gate.due(now_s):
            return intents
        iclcm: dict[str, object] = {}
        for event in self.active_events(now_s):
            if event.kind is RsuEventKind.ROADWORKS:
                intents.append(MessageIntent(IntentKind.DENM, self.unit_id, self.station_id, now_s, {
                    "cause_code": ROADWORKS_CAUSE, "x_m": event.x_m, "y_m": event.y_m,
                    "closed_lane": event.closed_lane, "length_m": event.length_m, "since_s": event.time_s,
                    # Valid from detection for as long as the works last, so repetitions never expire.
                    "validity_s": min(event.until_s - event.time_s, MAX_DENM_VALIDITY_S)}))
            elif event.kind is RsuEventKind.START_PLATOON:
                iclcm["start_platoon"] = event.platoon
            else:
                iclcm["end_of_scenario"] = True
        if iclcm:
            intents.append(MessageIntent(IntentKind.ICLCM, self.unit_id, self.station_id, now_s, iclcm))
        return intents
