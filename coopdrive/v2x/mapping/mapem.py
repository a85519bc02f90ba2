"""MAPEM (asn1tools value of TS 103 301's MAPEM) -> MapemContent: intersections, lanes with their nodes in metres,
connections with their signal groups. Road segments, restriction classes and regional data are not mapped."""

from __future__ import annotations

from coopdrive.v2x import units
from coopdrive.v2x.infrastructure import InfrastructureMessage
from coopdrive.v2x.mapping.common import bits_to_bools, bools_to_bits, set_optional
from coopdrive.v2x.mapping.dsrc_common import (
    header_into, header_to_asn, identified_into, identified_to_asn, intersection_into, intersection_to_asn)
from coopdrive.v2x.reasons import V2xEncodeError
from coopdrive.v1 import infrastructure_pb2 as pb

LANE_TYPE_OF_ALTERNATIVE = {
    "vehicle": pb.LANE_TYPE_VEHICLE, "crosswalk": pb.LANE_TYPE_CROSSWALK, "bikeLane": pb.LANE_TYPE_BIKE_LANE,
    "sidewalk": pb.LANE_TYPE_SIDEWALK, "median": pb.LANE_TYPE_MEDIAN, "striping": pb.LANE_TYPE_STRIPING,
    "trackedVehicle": pb.LANE_TYPE_TRACKED_VEHICLE, "parking": pb.LANE_TYPE_PARKING}
# NodeOffsetPointXY alternatives given as x/y offsets (Node-XY-20b to Node-XY-32b): all count centimetres.
_XY_NODES = ("node-XY1", "node-XY2", "node-XY3", "node-XY4", "node-XY5", "node-XY6")
_LATLON_NODE = "node-LatLon"
# The largest offset (cm) each of _XY_NODES holds: Offset-B10 to Offset-B16 (TS 103 301, ISO TS 19091).
_XY_NODE_LIMITS_CM = (511, 1023, 2047, 4095, 8191, 32767)
LANE_SHARING_BITS = 10
LANE_VEHICLE_ATTRIBUTE_BITS = 8
_ALTERNATIVE_OF_LANE_TYPE = {number: name for name, number in LANE_TYPE_OF_ALTERNATIVE.items()}


def mapem_from_asn(value: dict) -> pb.MapemContent:
    content = pb.MapemContent()
    header_into(value, content)
    data = value["map"]
    content.message_revision = data["msgIssueRevision"]
    set_optional(content, "minute_of_year", data.get("timeStamp"))
    for geometry in data.get("intersections", ()):
        _intersection_into(geometry, content.intersections.add())
    return content


def _intersection_into(value: dict, intersection: pb.MapIntersection) -> None:
    identified_into(value, intersection)
    reference = value["refPoint"]
    intersection.reference_latitude_deg = _degrees(units.LATITUDE_TENTH_MICRODEG, reference["lat"])
    intersection.reference_longitude_deg = _degrees(units.LONGITUDE_TENTH_MICRODEG, reference["long"])
    if "elevation" in reference:
        set_optional(intersection, "reference_elevation_m", units.DSRC_ELEVATION_DM.to_si(reference["elevation"]))
    if "laneWidth" in value:
        intersection.lane_width_m = units.DSRC_LANE_WIDTH_CM.to_si(value["laneWidth"])
    groups = set()
    for generic_lane in value["laneSet"]:
        lane = intersection.lanes.add()
        _lane_into(generic_lane, lane)
        groups.update(connection.signal_group for connection in lane.connections
                      if connection.HasField("signal_group"))
    intersection.signal_groups.extend(sorted(groups))


def _degrees(field: units.LinearField, count: int) -> float:
    """A reference point's latitude or longitude; 'unavailable' reads as NaN (the field is not optional)."""
    degrees = field.to_si(count)
    return float("nan") if degrees is None else degrees


def _lane_into(value: dict, lane: pb.Lane) -> None:
    lane.lane_id = value["laneID"]
    lane.name = value.get("name", "")
    set_optional(lane, "ingress_approach", value.get("ingressApproach"))
    set_optional(lane, "egress_approach", value.get("egressApproach"))
    attributes = value["laneAttributes"]
    direction = bits_to_bools(attributes["directionalUse"]) + [False, False]
    lane.ingress_path, lane.egress_path = direction[0], direction[1]
    lane.lane_type = LANE_TYPE_OF_ALTERNATIVE.get(attributes["laneType"][0], pb.LANE_TYPE_UNKNOWN)
    kind, nodes = value["nodeList"]
    if kind == "nodes":
        for node in nodes:
            _node_into(node["delta"], lane.nodes.add())
    elif kind == "computed":
        _computed_into(nodes, lane.computed)
    for connection in value.get("connectsTo", ()):
        _connection_into(connection, lane.connections.add())


def _node_into(delta: tuple, node: pb.LaneNode) -> None:
    kind, offset = delta
    if kind in _XY_NODES:
        node.east_m = units.DSRC_OFFSET_CM.to_si(offset["x"])
        node.north_m = units.DSRC_OFFSET_CM.to_si(offset["y"])
    elif kind == _LATLON_NODE:
        set_optional(node, "latitude_deg", units.LATITUDE_TENTH_MICRODEG.to_si(offset["lat"]))
        set_optional(node, "longitude_deg", units.LONGITUDE_TENTH_MICRODEG.to_si(offset["lon"]))
    # A regional node (or an alternative added after our module) has no position we can read: left empty.


def _computed_into(value: dict, computed: pb.ComputedLane) -> None:
    computed.reference_lane_id = value["referenceLaneId"]
    computed.offset_east_m = units.DSRC_OFFSET_CM.to_si(value["offsetXaxis"][1])
    computed.offset_north_m = units.DSRC_OFFSET_CM.to_si(value["offsetYaxis"][1])


def _connection_into(value: dict, connection: pb.LaneConnection) -> None:
    connection.to_lane_id = value["connectingLane"]["lane"]
    if "remoteIntersection" in value:
        intersection_into(value["remoteIntersection"], connection.remote_intersection)
    set_optional(connection, "signal_group", value.get("signalGroup"))
    set_optional(connection, "connection_id", value.get("connectionID"))


def mapem_to_asn(content: pb.MapemContent) -> dict:
    """The asn1tools value of a MAPEM whose lanes are node lists of x/y offsets (what the simulator's roadside unit
    sends); a lane given otherwise is refused with V2xEncodeError."""
    data = {"msgIssueRevision": content.message_revision,
            "intersections": [_intersection_to_asn(i) for i in content.intersections]}
    if content.HasField("minute_of_year"):
        data["timeStamp"] = content.minute_of_year
    return {"header": header_to_asn(content, InfrastructureMessage.MAPEM.message_id), "map": data}


def _intersection_to_asn(intersection: pb.MapIntersection) -> dict:
    value = identified_to_asn(intersection)
    value["refPoint"] = {"lat": units.LATITUDE_TENTH_MICRODEG.to_wire(intersection.reference_latitude_deg),
                         "long": units.LONGITUDE_TENTH_MICRODEG.to_wire(intersection.reference_longitude_deg)}
    if intersection.HasField("lane_width_m"):
        value["laneWidth"] = units.DSRC_LANE_WIDTH_CM.to_wire(intersection.lane_width_m)
    value["laneSet"] = [_lane_to_asn(lane) for lane in intersection.lanes]
    return value


def _lane_to_asn(lane: pb.Lane) -> dict:
    kind = _ALTERNATIVE_OF_LANE_TYPE.get(lane.lane_type)
    if kind is None or len(lane.nodes) < 2:
        raise V2xEncodeError(f"lane {lane.lane_id}: only lanes of a known type with two nodes or more are encoded")
    value = {"laneID": lane.lane_id, "laneAttributes": {
        "directionalUse": bools_to_bits([lane.ingress_path, lane.egress_path]),
        "sharedWith": bools_to_bits([False] * LANE_SHARING_BITS),
        "laneType": (kind, bools_to_bits([False] * LANE_VEHICLE_ATTRIBUTE_BITS))},
        "nodeList": ("nodes", [{"delta": _node_to_asn(lane, node)} for node in lane.nodes])}
    for field, wire_name in (("name", "name"), ("ingress_approach", "ingressApproach"),
                             ("egress_approach", "egressApproach")):
        if field == "name" and lane.name or field != "name" and lane.HasField(field):
            value[wire_name] = getattr(lane, field)
    if lane.connections:
        value["connectsTo"] = [_connection_to_asn(c) for c in lane.connections]
    return value


def _node_to_asn(lane: pb.Lane, node: pb.LaneNode) -> tuple[str, dict]:
    """The smallest Node-XY alternative that holds the offset (each node from the one before, the first from the
    reference point)."""
    if not (node.HasField("east_m") and node.HasField("north_m")):
        raise V2xEncodeError(f"lane {lane.lane_id}: a node without an x/y offset")
    x_cm, y_cm = round(node.east_m * 100.0), round(node.north_m * 100.0)
    for name, limit_cm in zip(_XY_NODES, _XY_NODE_LIMITS_CM):
        if max(abs(x_cm), abs(y_cm)) <= limit_cm:
            return name, {"x": x_cm, "y": y_cm}
    raise V2xEncodeError(f"lane {lane.lane_id}: a node offset of ({node.east_m}, {node.north_m}) m exceeds 327.67 m")


def _connection_to_asn(connection: pb.LaneConnection) -> dict:
    value: dict = {"connectingLane": {"lane": connection.to_lane_id}}
    if connection.HasField("remote_intersection"):
        value["remoteIntersection"] = intersection_to_asn(connection.remote_intersection)
    if connection.HasField("signal_group"):
        value["signalGroup"] = connection.signal_group
    if connection.HasField("connection_id"):
        value["connectionID"] = connection.connection_id
    return value
