import math

import pytest

from coopdrive.v2x.packet import GnParams, SourcePosition, decode_packet, encode_cam, encode_denm, encode_iclcm
from coopdrive.v1 import its_pb2

from .messages import cam, denm, flatten, iclcm

GN = GnParams(source_mac=bytes.fromhex("02000000002a"), time_tai_ms=123_456,
              source_position=SourcePosition(57.7, 11.9, 10.0, 0.0))


def assert_same_content(decoded, expected):
    got, want = flatten(decoded), flatten(expected)
    assert got.keys() == want.keys()
    for path, value in want.items():
        if isinstance(value, float):
            assert got[path] == pytest.approx(value, rel=1e-9, abs=1e-9), path
        else:
            assert got[path] == value, path


@pytest.mark.parametrize("top", [True, False], ids=["top", "bottom"])
@pytest.mark.parametrize("protocol_version", [1, 2])
def test_a_cam_with_every_field_at_a_range_limit_survives_the_round_trip(top, protocol_version):
    content = cam(top, protocol_version)
    decoded = decode_packet(encode_cam(content, GN))
    assert decoded.station_id == content.station_id
    assert_same_content(decoded.content, content)


@pytest.mark.parametrize("top", [True, False], ids=["top", "bottom"])
@pytest.mark.parametrize("protocol_version", [1, 2])
def test_a_denm_with_every_mapped_field_at_a_range_limit_survives_the_round_trip(top, protocol_version):
    content = denm(top, protocol_version)
    assert_same_content(decode_packet(encode_denm(content, GN)).content, content)


@pytest.mark.parametrize("top", [True, False], ids=["top", "bottom"])
def test_an_iclcm_with_every_field_at_a_range_limit_survives_the_round_trip(top):
    content = iclcm(top)
    assert_same_content(decode_packet(encode_iclcm(content, GN)).content, content)


def test_fields_left_unset_are_sent_as_unavailable_and_come_back_absent():
    content = its_pb2.CamContent(protocol_version=1, station_id=7)
    content.high_frequency.SetInParent()
    decoded = decode_packet(encode_cam(content, GN)).content
    assert not decoded.reference_position.HasField("latitude_deg")
    assert not decoded.high_frequency.HasField("speed_mps")
    assert not decoded.high_frequency.HasField("heading_rad")
    assert not decoded.high_frequency.HasField("lane_position")
    assert not decoded.HasField("low_frequency")


def test_an_iclcm_without_low_frequency_container_and_unavailable_values_decodes_as_such():
    content = its_pb2.IclcmContent(protocol_version=1, station_id=9, lane=2, intention=its_pb2.INTENTION_TURN_LEFT)
    decoded = decode_packet(encode_iclcm(content, GN)).content
    assert not decoded.has_low_frequency and not decoded.HasField("participants_ready")
    assert not decoded.HasField("cruise_speed_mps") and not decoded.HasField("time_headway_s")
    assert decoded.lane == 2 and decoded.intention == its_pb2.INTENTION_TURN_LEFT


def test_a_cam_without_vehicle_container_decodes_without_high_frequency():
    content = its_pb2.CamContent(protocol_version=1, station_id=15, station_type=its_pb2.STATION_TYPE_ROAD_SIDE_UNIT)
    content.reference_position.latitude_deg = 51.4
    decoded = decode_packet(encode_cam(content, GN)).content
    assert not decoded.HasField("high_frequency") and decoded.station_type == its_pb2.STATION_TYPE_ROAD_SIDE_UNIT


def test_out_of_range_values_are_clamped_when_encoding():
    content = its_pb2.CamContent(protocol_version=1, station_id=1)
    content.high_frequency.speed_mps = 400.0
    content.high_frequency.speed_confidence_mps = 7.0
    decoded = decode_packet(encode_cam(content, GN)).content.high_frequency
    assert decoded.speed_mps == pytest.approx(163.82)
    assert decoded.speed_confidence_mps == math.inf


def test_a_denm_sent_to_a_circle_carries_the_area_in_its_geo_broadcast_header():
    from coopdrive.v2x.geonet import GbcHeader, GeoAreaShape
    from coopdrive.v2x.packet import DestinationArea
    area = DestinationArea(51.45, 5.48, 300.0)
    params = GnParams(source_mac=GN.source_mac, source_position=GN.source_position, destination_area=area,
                      sequence_number=12)
    decoded = decode_packet(encode_denm(denm(False), params))
    assert isinstance(decoded.gn.extended, GbcHeader)
    assert decoded.gn.extended.area.shape == GeoAreaShape.CIRCLE
    assert decoded.gn.extended.area.latitude_tenth_microdeg == 514_500_000
    assert decoded.gn.extended.area.distance_a_m == 300 and decoded.gn.extended.sequence_number == 12


def test_an_extension_value_of_the_curvature_mode_newer_than_our_schema_reads_as_unavailable():
    from coopdrive.v2x.mapping.cam import cam_from_asn, cam_to_asn
    value = cam_to_asn(cam(True))
    value["cam"]["camParameters"]["highFrequencyContainer"][1]["curvatureCalculationMode"] = None
    decoded = cam_from_asn(value).high_frequency
    assert decoded.curvature_calculation_mode == its_pb2.CURVATURE_CALCULATION_MODE_UNAVAILABLE


def test_a_drive_direction_outside_the_enumeration_is_refused_by_the_mapping():
    from coopdrive.v2x.mapping.cam import cam_from_asn, cam_to_asn
    value = cam_to_asn(cam(True))
    value["cam"]["camParameters"]["highFrequencyContainer"][1]["driveDirection"] = None
    with pytest.raises(ValueError, match="unknown enumerated value"):
        cam_from_asn(value)
