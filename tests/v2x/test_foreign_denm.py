"""DENMs as another stack's encoder writes them (asn1tools on the ETSI modules, GBC from a roadside unit) decode."""

import asn1tools
import pytest

from coopdrive.v2x.btp import BtpBHeader, BtpPort
from coopdrive.v2x.geonet import (
    BasicHeader, CommonHeader, GbcHeader, GeoArea, GnAddress, GnPacket, LongPositionVector)
from coopdrive.v2x.packet import V2xPacketCodec
from tests.shared_data import shared_data_dir

STATION_ID = 12816437
ROADSIDE_UNIT = 15
ROAD_WORKS = {"causeCode": 3, "subCauseCode": 0}
POSITION = {"latitude": 478116792, "longitude": 131540307,
            "positionConfidenceEllipse": {"semiMajorConfidence": 100, "semiMinorConfidence": 50,
                                          "semiMajorOrientation": 900},
            "altitude": {"altitudeValue": 47660, "altitudeConfidence": "alt-001-00"}}
DELTA = {"deltaLatitude": 10, "deltaLongitude": -20, "deltaAltitude": 0}


@pytest.fixture(scope="module")
def etsi():
    asn1 = shared_data_dir().parent / "asn1"
    return asn1tools.compile_files([str(asn1 / "ITS_CAM_v1.3.2.asn"), str(asn1 / "ITS_DENM_v1.2.2.asn")], "uper")


def management(**optional) -> dict:
    return {"actionID": {"originatingStationID": STATION_ID, "sequenceNumber": 7}, "detectionTime": 599_000_000_000,
            "referenceTime": 599_000_000_100, "eventPosition": POSITION, "stationType": ROADSIDE_UNIT, **optional}


def minimal_denm() -> dict:
    """Every optional field absent, validityDuration left at its DEFAULT (so not encoded)."""
    return {"header": {"protocolVersion": 1, "messageID": 1, "stationID": STATION_ID},
            "denm": {"management": management()}}


def full_denm() -> dict:
    """Every optional field present, down to the a-la-carte containers our own encoder never fills."""
    alacarte = {
        "lanePosition": 2, "externalTemperature": 12, "positioningSolution": "dGNSS",
        "impactReduction": {
            "heightLonCarrLeft": 50, "heightLonCarrRight": 50, "posLonCarrLeft": 30, "posLonCarrRight": 30,
            "positionOfPillars": [10, 20], "posCentMass": 30, "wheelBaseVehicle": 27, "turningRadius": 60,
            "posFrontAx": 10, "positionOfOccupants": (b"\x80\x00\x00", 20), "vehicleMass": 150,
            "requestResponseIndication": "request"},
        "roadWorks": {
            "lightBarSirenInUse": (b"\x80", 2), "closedLanes": {"hardShoulderStatus": "closed",
                                                                "drivingLaneStatus": (b"\x40", 2)},
            "restriction": [5, 6], "speedLimit": 30, "incidentIndication": ROAD_WORKS,
            "recommendedPath": [POSITION], "startingPointSpeedLimit": DELTA, "trafficFlowRule": "passToLeft",
            "referenceDenms": [{"originatingStationID": 1, "sequenceNumber": 2}]},
        "stationaryVehicle": {
            "stationarySince": "lessThan2Minutes", "stationaryCause": ROAD_WORKS,
            "carryingDangerousGoods": {"dangerousGoodsType": "flammableLiquids", "unNumber": 1203,
                                       "elevatedTemperature": False, "tunnelsRestricted": True,
                                       "limitedQuantity": False, "emergencyActionCode": "3YE",
                                       "phoneNumber": "+4312345", "companyName": "Road Works Ltd"},
            "numberOfOccupants": 1, "vehicleIdentification": {"wMInumber": "WVW", "vDS": "ZZZ1KZ"},
            "energyStorageType": (b"\x40", 7)}}
    return {"header": {"protocolVersion": 1, "messageID": 1, "stationID": STATION_ID}, "denm": {
        "management": management(termination="isCancellation", relevanceDistance="lessThan500m",
                                 relevanceTrafficDirection="upstreamTraffic", validityDuration=3600,
                                 transmissionInterval=1000),
        "situation": {"informationQuality": 3, "eventType": ROAD_WORKS, "linkedCause": ROAD_WORKS,
                      "eventHistory": [{"eventPosition": DELTA, "eventDeltaTime": 100, "informationQuality": 2}]},
        "location": {"eventSpeed": {"speedValue": 0, "speedConfidence": 1},
                     "eventPositionHeading": {"headingValue": 900, "headingConfidence": 10},
                     "traces": [[{"pathPosition": DELTA, "pathDeltaTime": 50}]],
                     "roadType": "nonUrban-NoStructuralSeparationToOppositeLanes"},
        "alacarte": alacarte}}


def geo_broadcast(uper: bytes) -> bytes:
    """A GBC packet (circle of 500 m) from a roadside unit, as an RSU sends road works."""
    source = LongPositionVector(GnAddress(station_type=ROADSIDE_UNIT, mid=bytes.fromhex("020000c3a135")), 1000,
                                POSITION["latitude"], POSITION["longitude"], True, 0, 0)
    area = GeoArea(latitude_tenth_microdeg=POSITION["latitude"], longitude_tenth_microdeg=POSITION["longitude"],
                   distance_a_m=500)
    return GnPacket(BasicHeader(1), CommonHeader(), GbcHeader(3, source, area),
                    BtpBHeader(BtpPort.DENM).pack() + uper).to_bytes()


def test_a_denm_with_every_optional_field_absent_and_validity_duration_at_its_default_decodes(etsi):
    uper = etsi.encode("DENM", minimal_denm())
    decoded = V2xPacketCodec().decode_packet(geo_broadcast(uper))
    assert decoded.station_id == STATION_ID and decoded.content.originating_station_id == STATION_ID
    assert decoded.content.validity_duration_s == 600.0
    assert decoded.content.event_position.latitude_deg == pytest.approx(47.8116792)


def test_a_denm_with_every_optional_field_present_decodes_with_its_containers(etsi):
    uper = etsi.encode("DENM", full_denm())
    assert etsi.decode("DENM", uper) == full_denm()
    content = V2xPacketCodec().decode_packet(geo_broadcast(uper)).content
    assert content.validity_duration_s == 3600.0 and content.transmission_interval_s == 1.0
    assert content.situation.event_type.cause_code == 3 and len(content.location.traces) == 1
    assert content.alacarte.lane_position == 2
