"""SignalLanes: the intersections a vehicle heard of, drawn for Foxglove's Map panel as GeoJSON (WGS84, so a
recording of a real roadside unit draws where it stands, with no local map): every lane of each MAPEM, and each
signalised movement as a line across the box from its ingress lane's stop line to its egress lane, coloured by the
state its signal group has in the newest SPATEM of that intersection.

The colours are the signal heads' (green, amber, red, red-amber; a lighter green for a permissive green, yellow for
caution); a movement whose group no SPATEM heard within SPAT_SHOWN_FOR_S mentions is grey, so a lost SPaT shows.
Each feature carries `style` (color, weight, opacity: the Map panel's GeoJSON styling) and a `name` that says the
lane, the signal group and its state.
"""

from __future__ import annotations

import json

from foxglove_schemas_protobuf.GeoJSON_pb2 import GeoJSON

from coopdrive.geodesy import LocalTangentPlane
from coopdrive.roadmap.intersection_lanes import (Point, intersection_key, lane_points, leads_to_another_intersection,
                                                   reference_plane)
from coopdrive.v1 import infrastructure_pb2 as pb

IntersectionKey = tuple[int, int]

# A SPATEM's states older than this are drawn as unknown: roadside units send about 10 a second.
SPAT_SHOWN_FOR_S = 2.0
LANE_COLOR = "#c8c8c8"
NO_STATE_COLOR = "#8a8a8a"
STATE_COLORS = {
    pb.MOVEMENT_PHASE_STATE_PROTECTED_MOVEMENT_ALLOWED: "#12b34a",
    pb.MOVEMENT_PHASE_STATE_PERMISSIVE_MOVEMENT_ALLOWED: "#7fd88f",
    pb.MOVEMENT_PHASE_STATE_PROTECTED_CLEARANCE: "#ffab00",
    pb.MOVEMENT_PHASE_STATE_PERMISSIVE_CLEARANCE: "#ffab00",
    pb.MOVEMENT_PHASE_STATE_PRE_MOVEMENT: "#ff6d00",
    pb.MOVEMENT_PHASE_STATE_STOP_AND_REMAIN: "#e0201b",
    pb.MOVEMENT_PHASE_STATE_STOP_THEN_PROCEED: "#e0201b",
    pb.MOVEMENT_PHASE_STATE_CAUTION_CONFLICTING_TRAFFIC: "#ffe000",
}
LANE_WEIGHT_PX = 3
MOVEMENT_WEIGHT_PX = 6


class SignalLanes:
    def __init__(self) -> None:
        self._intersections: dict[IntersectionKey, tuple[pb.MapIntersection, LocalTangentPlane]] = {}
        # Per intersection: when its newest SPATEM was heard, and each signal group's current state in it.
        self._states: dict[IntersectionKey, tuple[float, dict[int, int]]] = {}

    def on_mapem(self, content: pb.MapemContent) -> None:
        for intersection in content.intersections:
            plane = reference_plane(intersection)
            if plane is not None:
                self._intersections[intersection_key(intersection.id)] = (intersection, plane)

    def on_spatem(self, content: pb.SpatemContent, heard_s: float) -> None:
        for intersection in content.intersections:
            states = {group.signal_group: group.events[0].state for group in intersection.signal_groups
                      if group.events}
            self._states[intersection_key(intersection.id)] = (heard_s, states)

    def geojson(self, now_s: float) -> GeoJSON | None:
        """Every mapped intersection as it stands at now_s; None before any MAPEM."""
        if not self._intersections:
            return None
        features = []
        for key, (intersection, plane) in sorted(self._intersections.items()):
            heard_s, states = self._states.get(key, (None, {}))
            if heard_s is None or now_s - heard_s > SPAT_SHOWN_FOR_S:
                states = {}
            features += _intersection_features(key, intersection, plane, states)
        return GeoJSON(geojson=json.dumps({"type": "FeatureCollection", "features": features}))


def _intersection_features(key: IntersectionKey, intersection: pb.MapIntersection, plane: LocalTangentPlane,
                           states: dict[int, int]) -> list[dict]:
    points = lane_points(intersection, plane)
    name = f"intersection {key[0]}/{key[1]}"
    features = [_line(plane, lane_nodes, f"{name} lane {lane_id}", LANE_COLOR, LANE_WEIGHT_PX)
                for lane_id, lane_nodes in sorted(points.items()) if len(lane_nodes) >= 2]
    for lane in intersection.lanes:
        for connection in lane.connections:
            across = _across_the_box(points, lane.lane_id, connection, key)
            if across is None or not connection.HasField("signal_group"):
                continue
            group = connection.signal_group
            state = states.get(group)
            state_name = "no SPaT" if state is None else pb.MovementPhaseState.Name(state)
            features.append(_line(plane, across, f"{name} lane {lane.lane_id} -> {connection.to_lane_id}, signal "
                                  f"group {group}: {state_name}", STATE_COLORS.get(state, NO_STATE_COLOR),
                                  MOVEMENT_WEIGHT_PX))
    return features


def _across_the_box(points: dict[int, tuple[Point, ...]], lane_id: int, connection: pb.LaneConnection,
                    key: IntersectionKey) -> tuple[Point, Point] | None:
    """From the ingress lane's stop line to the egress lane's first node, when both are in this MAP."""
    if leads_to_another_intersection(connection, key):
        return None
    ingress, egress = points.get(lane_id, ()), points.get(connection.to_lane_id, ())
    return (ingress[0], egress[0]) if ingress and egress else None


def _line(plane: LocalTangentPlane, points: tuple[Point, ...], name: str, color: str, weight_px: int) -> dict:
    coordinates = []
    for east_m, north_m in points:
        latitude_deg, longitude_deg, _ = plane.to_geodetic(east_m, north_m)
        coordinates.append([round(longitude_deg, 8), round(latitude_deg, 8)])
    return {"type": "Feature", "geometry": {"type": "LineString", "coordinates": coordinates},
            "properties": {"name": name, "style": {"color": color, "weight": weight_px, "opacity": 0.9}}}
