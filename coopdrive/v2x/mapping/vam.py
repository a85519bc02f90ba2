"""VAM (TS 103 300-3, Release 2 CDD) asn1tools dict -> VamContent: who the road user is, where and how it moves."""

from __future__ import annotations

from coopdrive.v2x import units
from coopdrive.v2x.mapping.common import set_optional
from coopdrive.v1 import its_pb2


def vam_from_asn(value: dict) -> its_pb2.VamContent:
    header, vam = value["header"], value["vam"]
    parameters = vam["vamParameters"]
    basic = parameters["basicContainer"]
    content = its_pb2.VamContent(protocol_version=header["protocolVersion"], station_id=header["stationId"],
                                 generation_delta_time_ms=vam["generationDeltaTime"], station_type=basic["stationType"])
    position = basic["referencePosition"]
    set_optional(content.reference_position, "latitude_deg", units.LATITUDE_TENTH_MICRODEG.to_si(position["latitude"]))
    set_optional(content.reference_position, "longitude_deg",
                 units.LONGITUDE_TENTH_MICRODEG.to_si(position["longitude"]))
    set_optional(content.reference_position, "altitude_m", units.ALTITUDE_CM.to_si(position["altitude"]["altitudeValue"]))
    high_frequency = parameters["vruHighFrequencyContainer"]
    set_optional(content, "speed_mps", units.SPEED_CMPS.to_si(high_frequency["speed"]["speedValue"]))
    if "heading" in high_frequency:  # Wgs84Angle: tenths of a degree clockwise from north, 3601 unavailable
        set_optional(content, "heading_rad", units.etsi_tenth_deg_to_heading_enu_rad(high_frequency["heading"]["value"]))
    if "longitudinalAcceleration" in high_frequency:
        set_optional(content, "longitudinal_acceleration_mps2", units.ACCELERATION_DECIMPS2.to_si(
            high_frequency["longitudinalAcceleration"]["longitudinalAccelerationValue"]))
    return content
