"""signal_world's intersection and phases written as TS 103 301 values, encoded by asn1tools compiled straight from
shared/asn1/dsrc (another encoder than ours) and decoded by our v2x path."""

from __future__ import annotations

from signal_world import AMBER, GREEN, LEFT, RED, RIGHT, STRAIGHT

from coopdrive.v2x.btp import BtpPort
from coopdrive.v2x.packet import decode_packet
from tests.v2x import infrastructure_messages as messages

STATE_NAME = {GREEN: "protected-Movement-Allowed", AMBER: "protected-clearance", RED: "stop-And-Remain"}
# NodeOffsetPointXY alternatives, the smallest first, and the largest offset (cm) each holds.
NODE_SIZES = (("node-XY1", 511), ("node-XY2", 1023), ("node-XY3", 2047), ("node-XY4", 4095), ("node-XY5", 8191),
              ("node-XY6", 32767))
UNKNOWN_TIME_MARK = 36001


def asn_lane(lane_id: int, offsets_m: list[tuple[float, float]], ingress: bool, connections=()) -> dict:
    nodes = []
    for east_m, north_m in offsets_m:
        x, y = round(east_m * 100), round(north_m * 100)
        kind = next(name for name, largest in NODE_SIZES if max(abs(x), abs(y)) <= largest)
        nodes.append({"delta": (kind, {"x": x, "y": y})})
    lane = {"laneID": lane_id, "laneAttributes": {"directionalUse": (b"\x80" if ingress else b"\x40", 2),
                                                  "sharedWith": messages.NO_SHARING,
                                                  "laneType": messages.VEHICLE_LANE},
            "nodeList": ("nodes", nodes)}
    if connections:
        lane["connectsTo"] = [{"connectingLane": {"lane": to}, "signalGroup": group} for to, group in connections]
    return lane


def asn_mapem() -> dict:
    """signal_world's intersection, written as TS 103 301's MAPEM."""
    lanes = [asn_lane(1, [(-10.0, -1.75), (-100.0, 0.0), (-200.0, 0.0)], True,
                      [(2, STRAIGHT), (3, LEFT), (4, RIGHT)]),
             asn_lane(2, [(10.0, -1.75), (100.0, 0.0)], False), asn_lane(3, [(1.75, 10.0), (0.0, 100.0)], False),
             asn_lane(4, [(-1.75, -10.0), (0.0, -100.0)], False)]
    intersection = {"id": {"id": 12}, "revision": 1, "refPoint": {"lat": 500_000_000, "long": 50_000_000},
                    "laneWidth": 350, "laneSet": lanes}
    return {"header": messages.header(2, 5), "map": {"msgIssueRevision": 1, "intersections": [intersection]}}


def asn_spatem(phases) -> dict:
    """Group 1 through (state, likely end in seconds of the hour), minEndTime unknown, as signal_world.light."""
    events = [{"eventState": STATE_NAME[state],
               "timing": {"minEndTime": UNKNOWN_TIME_MARK, "likelyTime": round(end_s * 10)}} for state, end_s in phases]
    intersection = {"id": {"id": 12}, "revision": 1, "status": (b"\x00\x00", 16),
                    "states": [{"signalGroup": 1, "state-time-speed": events}]}
    return {"header": messages.header(2, 4), "spat": {"intersections": [intersection]}}


def decoded(kind: str, value: dict):
    return decode_packet(messages.gn_packet(BtpPort[kind], messages.encoded(kind, value))).content
