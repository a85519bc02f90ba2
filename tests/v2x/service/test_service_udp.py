"""The V2xService over real UDP on 127.0.0.1 with a fake radio box, driven through an in-process context."""

import json
import logging
import socket
import subprocess
import time

import pytest

from coopdrive.runtime.testing import MemoryContext
from coopdrive.services.v2x.capture_decode import decode_capture
from coopdrive.v2x.geonet import GbcHeader
from coopdrive.v2x.packet import decode_packet
from coopdrive.services.v2x.send_file import send_from_yaml
from coopdrive.services.v2x.service import V2xService
from coopdrive.v1 import control_pb2, ego_pb2, its_pb2, planner_pb2, v2x_pb2

from ..test_tshark import tshark
from .streams import EPOCH_UNIX_S, REMOTE_STATION_ID, cam_packet, remote_cam
from tests.v2x.udp_socket import loopback_udp_socket

OWN_STATION_ID = 1001
START_S = 10.0
WAIT_S = 2.0


@pytest.fixture
def radio():
    box = loopback_udp_socket(WAIT_S)
    yield box
    box.close()


@pytest.fixture
def start_service(radio, tmp_path):
    """start_service(now_s, **config keys) -> (service, ctx); every service started is stopped at the end."""
    started = []

    def start(now_s: float, **overrides):
        ctx = MemoryContext(log=logging.getLogger("test.v2x"), queue_calls=True, opens_hardware=True)
        ctx.clock.set(now_s)
        config = V2xService.Config.model_validate({
            "link": {"radio_port": radio.getsockname()[1], "listen_port": 0}, "station_id": OWN_STATION_ID,
            "vehicle_mac": "02:00:00:00:00:01", "pcap_path": str(tmp_path / "v2x.pcap"), **overrides})
        service = V2xService(config, ctx)
        service.start()
        started.append(service)
        return service, ctx

    yield start
    for service in started:
        service.stop()


@pytest.fixture
def running(start_service, tmp_path):
    service, ctx = start_service(START_S, clock_epoch_utc="2016-05-28T10:00:00Z")
    return service, ctx, tmp_path / "v2x.pcap"


def exchange(service: V2xService, ctx: MemoryContext, radio: socket.socket) -> bytes:
    """Our CAM out to the radio, looped back by it, and one remote CAM in; returns our packet."""
    ctx.deliver("ego/state", ego_pb2.EgoState(x_m=5.0, y_m=2.0, heading_rad=0.2, speed_mps=15.0))
    service.transmit(START_S)
    ours, _ = radio.recvfrom(4096)
    listen = service.link.local_address
    radio.sendto(ours, listen)
    radio.sendto(cam_packet(remote_cam(START_S), START_S), listen)
    ctx.pump(2)
    return ours


def test_the_service_sends_our_cam_to_the_radio_box_and_publishes_it_on_v2x_tx(running, radio):
    service, ctx, _ = running
    ours = exchange(service, ctx, radio)
    decoded = decode_packet(ours)
    assert decoded.station_id == OWN_STATION_ID
    assert decoded.content.high_frequency.speed_mps == pytest.approx(15.0)
    assert [packet.payload for packet in ctx.messages("v2x/tx")] == [ours]


def test_a_remote_cam_from_the_radio_is_published_and_our_looped_back_one_is_ignored(running, radio):
    service, ctx, _ = running
    exchange(service, ctx, radio)
    assert ctx.messages("v2x/cam") == []  # socket input is only published by the flush trigger
    ctx.clock.set(START_S + 0.02)
    service.flush_received(ctx.now_s())
    assert [cam.station_id for cam in ctx.messages("v2x/cam")] == [REMOTE_STATION_ID]
    assert [packet.direction for packet in ctx.messages("v2x/rx")] == [v2x_pb2.PACKET_DIRECTION_RECEIVED] * 2
    service.publish_status(ctx.now_s())
    status = ctx.messages("v2x/status")[-1]
    assert [(s.station_id, s.state) for s in status.stations] == [(REMOTE_STATION_ID, v2x_pb2.LINK_STATE_ACTIVE)]
    assert (status.packets_sent, status.packets_received) == (1, 2)
    assert service.counters["own_packets_ignored"] == 1


def test_the_pcap_the_service_writes_decodes_with_tshark_to_the_station_ids_sent(running, radio):
    service, ctx, pcap = running
    exchange(service, ctx, radio)
    service.stop()
    result = subprocess.run([tshark(), "-r", str(pcap), "-T", "fields", "-e", "eth.src", "-e", "eth.type",
                             "-e", "its.stationID"], check=True, capture_output=True, text=True, timeout=60)
    rows = [line.split("\t") for line in result.stdout.splitlines()]
    assert rows == [["02:00:00:00:00:01", "0x8947", str(OWN_STATION_ID)],
                    ["02:00:00:00:00:01", "0x8947", str(OWN_STATION_ID)],
                    ["02:00:00:00:00:2a", "0x8947", str(REMOTE_STATION_ID)]]


def test_decode_capture_lists_the_service_pcap_as_text_and_as_json(running, radio):
    service, ctx, pcap = running
    exchange(service, ctx, radio)
    service.stop()
    lines = list(decode_capture(pcap))
    assert lines[3] == "summary:" and f"cam station {REMOTE_STATION_ID}" in lines[2]
    records = [json.loads(line) for line in decode_capture(pcap, as_json=True)][:-1]
    assert [r["station_id"] for r in records] == [OWN_STATION_ID, OWN_STATION_ID, REMOTE_STATION_ID]
    assert records[0]["time_s"] == pytest.approx(EPOCH_UNIX_S + START_S)
    assert records[2]["content"]["high_frequency"]["speed_mps"] == pytest.approx(20.0)


def test_send_from_yaml_injects_an_iclcm_the_service_publishes(start_service, tmp_path):
    # The sender stamps wall time, so this service runs on the wall clock (no epoch).
    service, ctx = start_service(time.time())
    description = tmp_path / "iclcm.yaml"
    description.write_text("type: iclcm\ngn: {source_mac: '02:00:00:00:00:07'}\n"
                           "content: {station_id: 7, controller_type: CONTROLLER_TYPE_CACC, time_headway_s: 0.5}\n")
    send_from_yaml(description, *service.link.local_address)
    ctx.pump(1)
    service.flush_received(ctx.now_s())
    [iclcm] = ctx.messages("v2x/iclcm")
    assert (iclcm.station_id, iclcm.controller_type, iclcm.time_headway_s) == (7, its_pb2.CONTROLLER_TYPE_CACC, 0.5)


def test_the_service_sends_an_iclcm_from_the_behaviour_and_the_command(running, radio):
    service, ctx, _ = running
    ctx.deliver("planner/behaviour", planner_pb2.BehaviourRequest(iclcm=planner_pb2.IclcmIntent(platoon_id=2)))
    ctx.deliver("control/command", control_pb2.ControlCommand(longitudinal_mode=control_pb2.LONGITUDINAL_MODE_ACC))
    service.transmit(START_S)
    decoded = decode_packet(radio.recvfrom(4096)[0])
    assert decoded.content.platoon_id == 2
    assert decoded.content.controller_type == its_pb2.CONTROLLER_TYPE_ACC


def test_the_service_publishes_only_from_the_time_triggers_it_registered(running):
    service, ctx, _ = running
    periods_s = ctx.trigger_periods_s()
    assert set(periods_s) == {"transmit", "flush_received", "publish_status"}
    assert periods_s["publish_status"] == pytest.approx(0.2)


def test_a_denm_triggered_through_the_service_is_geo_broadcast_around_its_event(running, radio):
    service, ctx, _ = running
    event = its_pb2.DenmContent(relevance_distance=its_pb2.RELEVANCE_DISTANCE_LESS_THAN_200M, validity_duration_s=5.0)
    event.event_position.latitude_deg, event.event_position.longitude_deg = 51.46, 5.63
    event.situation.event_type.cause_code = 3
    action = service.trigger_denm(event, repetition_interval_s=0.04)
    service.transmit(START_S)
    decoded = decode_packet(radio.recvfrom(4096)[0])
    assert isinstance(decoded.gn.extended, GbcHeader) and decoded.gn.extended.area.distance_a_m == 200
    assert (decoded.content.originating_station_id, decoded.content.sequence_number) == \
        (OWN_STATION_ID, action.sequence_number)
    service.cancel_denm(action)
    service.transmit(START_S + 0.04)
    assert decode_packet(radio.recvfrom(4096)[0]).content.termination == its_pb2.DENM_TERMINATION_CANCELLATION


def test_a_received_cam_is_published_at_its_generation_time_not_when_it_arrived(running, radio):
    service, ctx, _ = running
    generated_s = START_S - 0.06  # 60 ms in the air and the sender's queue: 1.2 m at 20 m/s
    radio.sendto(cam_packet(remote_cam(generated_s), generated_s), service.link.local_address)
    ctx.pump(1)
    service.flush_received(START_S + 0.02)
    assert [m.header.sample_time_s for m in ctx.messages("v2x/cam")] == [pytest.approx(generated_s, abs=1e-3)]
    assert [m.header.sample_time_s for m in ctx.messages("v2x/rx")] == [START_S]
