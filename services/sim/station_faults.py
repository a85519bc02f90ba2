"""V2X station faults the simulator carries out in what participants broadcast: a ghost vehicle (CAMs from a
station that does not exist) and a station whose CAMs are offset from where it is.

Both change only the messages: the ground truth, the sensors and the judge see the world as it is, so a run
shows whether the stacks believed the lie (a ghost must never become an MIO, and its trust must fall).
"""

from __future__ import annotations

import math
from collections.abc import Sequence

from coopdrive.services.sim.fault_config import Fault, GhostVehicle, PositionOffset
from coopdrive.messages.vehicle_frame import rear_overhang_m
from coopdrive.services.sim.participants import IntentKind, MessageIntent, RateGate
from coopdrive.v1 import sim_pb2

GHOST_LENGTH_M = 4.5
GHOST_WIDTH_M = 1.8


def ghost_sender(fault: GhostVehicle) -> str:
    """The radio node a ghost transmits as (no vehicle of the run has this id)."""
    return f"ghost-{fault.station_id}"


class StationFaults:
    def __init__(self, faults: Sequence[Fault]) -> None:
        self.ghosts = [f for f in faults if isinstance(f, GhostVehicle)]
        self.offsets = [f for f in faults if isinstance(f, PositionOffset)]
        self._gates = {id(f): RateGate(f.rate_hz, f.start_s) for f in self.ghosts}

    def apply(self, intents: list[MessageIntent], now_s: float,
              truths: Sequence[sim_pb2.VehicleTruth]) -> list[MessageIntent]:
        """The intents as the faults active at now_s make them, ghosts' CAMs added."""
        shifted = [self._offset(intent, now_s) for intent in intents]
        by_id = {truth.vehicle_id: truth for truth in truths}
        for fault in self.ghosts:
            target = by_id.get(fault.vehicle_id)
            if target is not None and fault.active(now_s) and self._gates[id(fault)].due(now_s):
                shifted.append(MessageIntent(IntentKind.CAM, ghost_sender(fault), fault.station_id, now_s,
                                             _ghost_fields(fault, target)))
        return shifted

    def positions(self, now_s: float, truths: Sequence[sim_pb2.VehicleTruth]) -> dict[str, tuple[float, float]]:
        """Where each active ghost transmits from: where it claims to be."""
        by_id = {truth.vehicle_id: truth for truth in truths}
        positions = {}
        for fault in self.ghosts:
            target = by_id.get(fault.vehicle_id)
            if target is not None and fault.active(now_s):
                fields = _ghost_fields(fault, target)
                positions[ghost_sender(fault)] = (fields["x_m"], fields["y_m"])
        return positions

    def _offset(self, intent: MessageIntent, now_s: float) -> MessageIntent:
        if intent.kind is not IntentKind.CAM:
            return intent
        offsets = [f for f in self.offsets if f.vehicle_id == intent.sender_id and f.active(now_s)]
        if not offsets:
            return intent
        fields = dict(intent.fields)
        fields["x_m"] += sum(f.east_m for f in offsets)
        fields["y_m"] += sum(f.north_m for f in offsets)
        return MessageIntent(intent.kind, intent.sender_id, intent.station_id, intent.time_s, fields)


def _ghost_fields(fault: GhostVehicle, target: sim_pb2.VehicleTruth) -> dict:
    """A car whose rear bumper is gap_m ahead of the target's front bumper: CAM reference point (rear axle)."""
    front_m = target.length_m - rear_overhang_m(target.length_m)
    ahead_m = front_m + fault.gap_m + rear_overhang_m(GHOST_LENGTH_M)
    cos_h, sin_h = math.cos(target.heading_rad), math.sin(target.heading_rad)
    return {"x_m": target.x_m + ahead_m * cos_h - fault.lateral_m * sin_h,
            "y_m": target.y_m + ahead_m * sin_h + fault.lateral_m * cos_h,
            "heading_rad": target.heading_rad, "speed_mps": target.speed_mps, "accel_mps2": 0.0,
            "yaw_rate_radps": target.yaw_rate_radps, "length_m": GHOST_LENGTH_M, "width_m": GHOST_WIDTH_M,
            "lane": target.lane_index}
