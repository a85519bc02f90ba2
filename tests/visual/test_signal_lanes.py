"""Foxglove draws the MAP's lanes with each signalised movement coloured by its signal group's state in the newest
SPaT (coopdrive/visual/signal_lanes.py), here with the real roadside unit's signed SPATEM from shared/data."""

import json

import pytest

from coopdrive.bus.keys import KeyLayout
from coopdrive.geodesy import LocalTangentPlane
from coopdrive.recording.capture import read_gn_packets
from coopdrive.v1 import infrastructure_pb2 as pb
from coopdrive.v2x.packet import decode_packet
from coopdrive.visual.channels import VisualChannels
from coopdrive.visual.signal_lanes import NO_STATE_COLOR, SPAT_SHOWN_FOR_S, STATE_COLORS, SignalLanes
from tests.shared_data import shared_file

# The real SPATEM's intersection (region 30, id 63); its signal group 1 is red when it was sent.
REGION, INTERSECTION, GROUP = 30, 63, 1
REFERENCE = (48.2, 16.37)
STOP_LINE_M = (-10.0, -1.75)


def real_spatem() -> pb.SpatemContent:
    packets = [packet.gn_packet for packet in read_gn_packets(shared_file("v2x/considerit_signed_testvectors.pcap"))]
    return decode_packet(packets[3]).content


def mapem() -> pb.MapemContent:
    """An ingress lane (1) whose straight movement to lane 2 is the real SPaT's group 1."""
    content = pb.MapemContent(station_id=10430022)
    intersection = content.intersections.add(reference_latitude_deg=REFERENCE[0],
                                             reference_longitude_deg=REFERENCE[1])
    intersection.id.region, intersection.id.id = REGION, INTERSECTION
    ingress = intersection.lanes.add(lane_id=1, ingress_path=True, lane_type=pb.LANE_TYPE_VEHICLE)
    for east_m, north_m in (STOP_LINE_M, (-90.0, 1.75)):  # each node from the one before
        ingress.nodes.add(east_m=east_m, north_m=north_m)
    ingress.connections.add(to_lane_id=2, signal_group=GROUP)
    egress = intersection.lanes.add(lane_id=2, egress_path=True, lane_type=pb.LANE_TYPE_VEHICLE)
    for east_m, north_m in ((10.0, -1.75), (90.0, 0.0)):
        egress.nodes.add(east_m=east_m, north_m=north_m)
    return content


def features(lanes: SignalLanes, now_s: float) -> dict[str, dict]:
    return {feature["properties"]["name"]: feature for feature in json.loads(lanes.geojson(now_s).geojson)["features"]}


def test_the_real_rsus_red_colours_its_groups_movement_across_the_box_from_the_stop_line():
    lanes = SignalLanes()
    lanes.on_mapem(mapem())
    lanes.on_spatem(real_spatem(), heard_s=100.0)
    drawn = features(lanes, now_s=100.5)
    movement = drawn[f"intersection {REGION}/{INTERSECTION} lane 1 -> 2, signal group {GROUP}: "
                     "MOVEMENT_PHASE_STATE_STOP_AND_REMAIN"]
    assert movement["properties"]["style"]["color"] == STATE_COLORS[pb.MOVEMENT_PHASE_STATE_STOP_AND_REMAIN]
    (start_lon, start_lat), (end_lon, end_lat) = movement["geometry"]["coordinates"]
    plane = LocalTangentPlane(*REFERENCE)
    assert plane.to_enu(start_lat, start_lon)[:2] == pytest.approx(STOP_LINE_M, abs=0.01)
    assert plane.to_enu(end_lat, end_lon)[:2] == pytest.approx((10.0, -1.75), abs=0.01)
    ingress = drawn[f"intersection {REGION}/{INTERSECTION} lane 1"]["geometry"]["coordinates"]
    assert plane.to_enu(ingress[1][1], ingress[1][0])[:2] == pytest.approx((-100.0, 0.0), abs=0.01)


def test_a_spat_older_than_the_shown_time_leaves_the_movement_grey_and_says_so():
    lanes = SignalLanes()
    lanes.on_mapem(mapem())
    lanes.on_spatem(real_spatem(), heard_s=100.0)
    drawn = features(lanes, now_s=100.0 + SPAT_SHOWN_FOR_S + 0.1)
    (movement,) = [f for name, f in drawn.items() if "signal group" in name]
    assert movement["properties"]["name"].endswith("no SPaT")
    assert movement["properties"]["style"]["color"] == NO_STATE_COLOR


def test_a_spat_of_an_intersection_no_map_described_draws_nothing():
    lanes = SignalLanes()
    lanes.on_spatem(real_spatem(), heard_s=0.0)
    assert lanes.geojson(0.0) is None


def test_the_channels_send_the_vehicles_signals_on_each_mapem_and_spatem_in_foxgloves_geojson_schema():
    sent = []
    layout = KeyLayout()
    channels = VisualChannels(lambda topic, message, time_ns: sent.append((topic, message, time_ns)))
    spat = real_spatem()
    for topic, message, at_s in (("v2x/spatem", spat, 0.9), ("v2x/mapem", mapem(), 1.0), ("v2x/spatem", spat, 1.1)):
        message.header.sent_time_s = at_s
        channels.on_message(layout.topic("car1", topic), message, round(at_s * 1e9))
    channels.flush()
    assert [(topic, type(message).DESCRIPTOR.full_name) for topic, message, _ in sent] == [
        ("foxglove/car1/signals", "foxglove.GeoJSON")] * 2
    colours = [[f["properties"]["style"]["color"] for f in json.loads(message.geojson)["features"]
                if "signal group" in f["properties"]["name"]] for _, message, _ in sent]
    # The SPATEM heard before the MAPEM still colours the movement once the MAPEM draws it.
    assert colours == [[STATE_COLORS[pb.MOVEMENT_PHASE_STATE_STOP_AND_REMAIN]]] * 2
