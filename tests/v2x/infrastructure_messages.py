"""MAPEM, SPATEM, SREM and SSEM written by hand as asn1tools values of TS 103 301's modules and encoded by asn1tools
compiled straight from the standard's text in shared/asn1/dsrc: another encoder than ours, and no code of our
mappings involved. Each value's expected protobuf is spelled out in the tests, in SI units."""

from __future__ import annotations

import functools

import asn1tools

from coopdrive.v2x.btp import BtpBHeader, BtpPort
from coopdrive.v2x.geonet import BasicHeader, CommonHeader, GnAddress, GnPacket, LongPositionVector, ShbHeader
from tests.shared_data import shared_data_dir

DSRC_FILES = ("ETSI-ITS-CDD_TS102894-2v231.asn", "ETSI-ITS-DSRC_TS103301v221.asn",
              "ETSI-ITS-DSRC-AddGrpC_TS103301v221.asn", "ETSI-ITS-DSRC-REGION_TS103301v221.asn",
              "MAPEM-PDU-Descriptions_TS103301v211-adapted.asn", "SPATEM-PDU-Descriptions_TS103301v211-adapted.asn",
              "SREM-PDU-Descriptions_TS103301v211-adapted.asn", "SSEM-PDU-Descriptions_TS103301v211-adapted.asn")
RSU_STATION = 777
RSU_MAC = bytes.fromhex("02000000a0a0")
ADD_GRP_C = 3
ADD_GRP_A = 1
VEHICLE_LANE = ("vehicle", (b"\x00", 8))
NO_SHARING = (b"\x00\x00", 10)


@functools.cache
def standard_encoder() -> asn1tools.compiler.Specification:
    folder = shared_data_dir().parent / "asn1" / "dsrc"
    return asn1tools.compile_files([str(folder / name) for name in DSRC_FILES], "uper")


def header(protocol_version: int, message_id: int) -> dict:
    return {"protocolVersion": protocol_version, "messageId": message_id, "stationId": RSU_STATION}


def mapem(protocol_version: int = 2) -> dict:
    """One intersection (region 7, id 1234) at 57.7081234 N 11.9393456 E, 12.3 m: lane 1 an ingress vehicle lane of
    three nodes (20b and 32b offsets, an absolute node) with two connections; lane 2 a crosswalk computed from it."""
    lane_1 = {"laneID": 1, "ingressApproach": 1,
              "laneAttributes": {"directionalUse": (b"\x80", 2), "sharedWith": NO_SHARING, "laneType": VEHICLE_LANE},
              "nodeList": ("nodes", [{"delta": ("node-XY1", {"x": -150, "y": 20})},
                                     {"delta": ("node-XY6", {"x": 0, "y": -3000})},
                                     {"delta": ("node-LatLon", {"lon": 119390000, "lat": 577080000})}]),
              "connectsTo": [{"connectingLane": {"lane": 5}, "signalGroup": 4, "connectionID": 9},
                             {"connectingLane": {"lane": 6}, "remoteIntersection": {"id": 99}, "signalGroup": 2}]}
    lane_2 = {"laneID": 2, "egressApproach": 2, "name": "north crossing",
              "laneAttributes": {"directionalUse": (b"\xc0", 2), "sharedWith": NO_SHARING,
                                 "laneType": ("crosswalk", (b"\x00\x00", 16))},
              "nodeList": ("computed", {"referenceLaneId": 1, "offsetXaxis": ("small", 350),
                                        "offsetYaxis": ("large", -4000)})}
    intersection = {"id": {"region": 7, "id": 1234}, "revision": 5, "name": "Lindholmen",
                    "refPoint": {"lat": 577081234, "long": 119393456, "elevation": 123},
                    "laneWidth": 350, "laneSet": [lane_1, lane_2]}
    return {"header": header(protocol_version, 5),
            "map": {"timeStamp": 100000, "msgIssueRevision": 3, "intersections": [intersection]}}


def spatem(protocol_version: int = 2) -> dict:
    """Intersection 1234 in fixed-time operation: group 4 green until 120.0 to 135.0 s of the hour (likely 127.5),
    then clearance with an unknown end; group 2 red with no timing. Two regional extensions: addGrpC's, and one
    of addGrpA (not in our module: left undecoded)."""
    add_grp_c = standard_encoder().encode("IntersectionState-addGrpC", {"activePrioritizations": [
        {"stationID": 4242, "priorState": "granted", "signalGroup": 4}]})
    intersection = {"id": {"id": 1234}, "revision": 6, "status": (b"\x04\x00", 16), "moy": 200000,
                    "timeStamp": 30500,
                    "states": [{"signalGroup": 4, "state-time-speed": [
                        {"eventState": "protected-Movement-Allowed",
                         "timing": {"minEndTime": 1200, "maxEndTime": 1350, "likelyTime": 1275, "confidence": 10}},
                        {"eventState": "protected-clearance", "timing": {"minEndTime": 36001}}]},
                        {"signalGroup": 2, "movementName": "left turn",
                         "state-time-speed": [{"eventState": "stop-And-Remain"}]}],
                    "regional": [{"regionId": ADD_GRP_C, "regExtValue": add_grp_c},
                                 {"regionId": ADD_GRP_A, "regExtValue": b"\x12\x34\x56"}]}
    return {"header": header(protocol_version, 4), "spat": {"timeStamp": 200000, "intersections": [intersection]}}


def srem(protocol_version: int = 2) -> dict:
    """A bus (station 4242, role publicTransport) asks intersection 1234 for priority from lane 1 to approach 3."""
    request = {"id": {"id": 1234}, "requestID": 17, "requestType": "priorityRequest", "inBoundLane": ("lane", 1),
               "outBoundLane": ("approach", 3)}
    return {"header": header(protocol_version, 9),
            "srm": {"timeStamp": 200000, "second": 30500, "sequenceNumber": 8, "requests": [{"request": request}],
                    "requestor": {"id": ("stationID", 4242), "type": {"role": "publicTransport"}}}}


def ssem(protocol_version: int = 2) -> dict:
    """Intersection 1234 grants request 17 of station 4242."""
    package = {"requester": {"id": ("stationID", 4242), "request": 17, "sequenceNumber": 8,
                             "role": "publicTransport"},
               "inboundOn": ("lane", 1), "status": "granted"}
    return {"header": header(protocol_version, 10),
            "ssm": {"second": 31000, "status": [{"sequenceNumber": 2, "id": {"id": 1234}, "sigStatus": [package]}]}}


def encoded(type_name: str, value: dict) -> bytes:
    return standard_encoder().encode(type_name, value, check_constraints=True)


def gn_packet(port: BtpPort, uper: bytes, mac: bytes = RSU_MAC) -> bytes:
    """The UPER in an unsecured GN single-hop broadcast from a roadside unit (station type 15)."""
    source = LongPositionVector(GnAddress(station_type=15, mid=mac), 0, 577081234, 119393456, True, 0, 0)
    return GnPacket(BasicHeader(1), CommonHeader(), ShbHeader(source),
                    BtpBHeader(int(port)).pack() + uper).to_bytes()
