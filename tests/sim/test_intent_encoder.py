"""Scripted participants' broadcasts become real GN packets that the stack's own V2X decoder reads."""

import datetime as dt
import math

import pytest

from coopdrive.roadmap import RoadMap
from coopdrive.messages.vehicle_frame import rear_overhang_m
from coopdrive.services.sim.intent_encoder import IntentEncoder
from coopdrive.services.sim.participants import IntentKind, MessageIntent
from coopdrive.v2x.packet import decode_packet
from coopdrive.v1 import its_pb2

EPOCH = dt.datetime(2016, 5, 28, 10, 0, tzinfo=dt.timezone.utc)
CAR = {"x_m": 120.0, "y_m": 15.0, "heading_rad": 0.3, "speed_mps": 22.0, "accel_mps2": -0.5,
       "yaw_rate_radps": 0.01, "length_m": 4.5, "width_m": 1.8, "lane": 0}


@pytest.fixture(scope="module")
def road_map():
    return RoadMap.load("a270")


@pytest.fixture
def encoder(road_map):
    return IntentEncoder(road_map.to_geodetic, EPOCH)


def test_a_scripted_cam_decodes_with_its_station_position_speed_and_heading(encoder, road_map):
    packet = encoder.encode(MessageIntent(IntentKind.CAM, "lead", 2001, 1.0, dict(CAR)))
    decoded = decode_packet(packet)
    cam = decoded.content
    assert decoded.station_id == 2001 and isinstance(cam, its_pb2.CamContent)
    # The reference point is the centre of the front: the rear axle (x_m, y_m) plus the axle-to-front distance.
    ahead_m = CAR["length_m"] - rear_overhang_m(CAR["length_m"])
    latitude_deg, longitude_deg, _ = road_map.to_geodetic(120.0 + ahead_m * math.cos(0.3), 15.0 + ahead_m * math.sin(0.3))
    assert cam.reference_position.latitude_deg == pytest.approx(latitude_deg, abs=3e-7)
    assert cam.reference_position.longitude_deg == pytest.approx(longitude_deg, abs=3e-7)
    assert cam.high_frequency.speed_mps == pytest.approx(22.0, abs=0.01)
    # ENU yaw 0.3 rad from east is an ETSI heading of 90 - 17.19 deg from north; the codec converts back.
    assert math.remainder(cam.high_frequency.heading_rad - 0.3, math.tau) == pytest.approx(0.0, abs=0.002)


def test_the_same_cam_period_is_not_sent_twice(encoder):
    assert encoder.encode(MessageIntent(IntentKind.CAM, "lead", 2001, 1.0, dict(CAR))) is not None
    assert encoder.encode(MessageIntent(IntentKind.CAM, "lead", 2001, 1.02, dict(CAR))) is None
    assert encoder.encode(MessageIntent(IntentKind.CAM, "lead", 2001, 1.04, dict(CAR))) is not None


def test_a_road_works_denm_is_geo_broadcast_from_the_roadside_unit_with_its_cause_and_lane(encoder):
    fields = {"cause_code": 3, "x_m": 1477.0, "y_m": 260.0, "closed_lane": 1, "length_m": 300.0, "since_s": 10.0}
    decoded = decode_packet(encoder.encode(MessageIntent(IntentKind.DENM, "rsu", 3000, 12.0, fields)))
    denm = decoded.content
    assert denm.situation.event_type.cause_code == 3
    assert denm.alacarte.lane_position == 1
    assert denm.station_type == its_pb2.STATION_TYPE_ROAD_SIDE_UNIT
    assert denm.reference_time_tai_ms - denm.detection_time_tai_ms == 2000


def test_a_denm_states_the_validity_its_sender_gives_else_ten_seconds(encoder):
    fields = {"cause_code": 3, "x_m": 1477.0, "y_m": 260.0, "closed_lane": 1, "since_s": 10.0}
    plain = decode_packet(encoder.encode(MessageIntent(IntentKind.DENM, "rsu", 3000, 12.0, fields))).content
    lasting = decode_packet(encoder.encode(MessageIntent(IntentKind.DENM, "rsu", 3000, 12.0,
                                                         {**fields, "validity_s": 3600.0}))).content
    assert (plain.validity_duration_s, lasting.validity_duration_s) == (10, 3600)


def test_a_start_platoon_iclcm_from_the_roadside_unit_carries_the_platoon(encoder):
    intent = MessageIntent(IntentKind.ICLCM, "rsu", 3000, 2.0, {"start_platoon": 1})
    iclcm = decode_packet(encoder.encode(intent)).content
    assert iclcm.station_id == 3000 and iclcm.start_platoon == 1 and not iclcm.end_of_scenario


def test_encoding_is_deterministic(road_map):
    def packets():
        encoder = IntentEncoder(road_map.to_geodetic, EPOCH)
        return [encoder.encode(MessageIntent(IntentKind.CAM, "lead", 2001, t / 25, dict(CAR))) for t in range(5)]

    assert packets() == packets()


def test_an_unknown_field_is_refused_by_name(encoder):
    with pytest.raises(ValueError, match="hazard_lights"):
        encoder.encode(MessageIntent(IntentKind.CAM, "lead", 2001, 1.0, dict(CAR, hazard_lights=True)))


@pytest.mark.parametrize("gn_version", [0, 1])
def test_both_gn_versions_decode(road_map, gn_version):
    encoder = IntentEncoder(road_map.to_geodetic, EPOCH, gn_version=gn_version)
    assert decode_packet(encoder.encode(MessageIntent(IntentKind.CAM, "lead", 2001, 1.0, dict(CAR)))).station_id == 2001


def test_the_road_works_denm_area_is_centred_on_the_event(encoder, road_map):
    fields = {"cause_code": 3, "x_m": 1477.0, "y_m": 260.0, "closed_lane": 1, "length_m": 300.0, "since_s": 10.0}
    decoded = decode_packet(encoder.encode(MessageIntent(IntentKind.DENM, "rsu", 3000, 12.0, fields)))
    area = decoded.gn.extended.area
    latitude_deg, longitude_deg, _ = road_map.to_geodetic(1477.0, 260.0)
    assert area.latitude_tenth_microdeg * 1e-7 == pytest.approx(latitude_deg, abs=1e-6)
    assert area.longitude_tenth_microdeg * 1e-7 == pytest.approx(longitude_deg, abs=1e-6)
    assert area.distance_a_m > 0 and decoded.btp.destination_port != 0
