import json
import subprocess

import pytest

from coopdrive.services.v2x.capture_decode import decode_capture
from coopdrive.services.v2x.send_file import SendFileError, load_send_file, packet_from_send_file, send_from_yaml
from coopdrive.v2x.its_pdu import ItsMessageId
from coopdrive.v2x.packet import decode_packet
from coopdrive.v2x.pcap import PcapWriter
from coopdrive.v2x.timebase import tai_ms_from_unix_s
from coopdrive.v1 import its_pb2

from ..test_tshark import tshark
from .streams import REMOTE_MAC, cam_packet, remote_cam
from tests.v2x.udp_socket import loopback_udp_socket

UNIX_S = 1_700_000_000.0

CAM_YAML = """
type: cam
gn: {source_mac: "02:00:00:00:00:2a", gn_version: 1}
content:
  protocol_version: 2
  station_id: 42
  reference_position: {latitude_deg: 51.45, longitude_deg: 5.48}
  high_frequency: {speed_mps: 13.9, heading_rad: 1.57}
"""

DENM_YAML = """
type: denm
content:
  station_id: 99
  originating_station_id: 99
  event_position: {latitude_deg: 51.45, longitude_deg: 5.48}
  validity_duration_s: 60
  situation: {information_quality: 3, event_type: {cause_code: 3}}
"""


def write(tmp_path, name, text):
    path = tmp_path / name
    path.write_text(text)
    return path


def test_a_cam_yaml_becomes_a_gn_packet_with_its_settings_and_the_time_filled_in(tmp_path):
    packet = packet_from_send_file(load_send_file(write(tmp_path, "cam.yaml", CAM_YAML)), UNIX_S)
    decoded = decode_packet(packet)
    assert decoded.gn.basic.version == 1 and decoded.its_header.protocol_version == 2
    assert bytes(decoded.gn.extended.source_position.address.mid) == REMOTE_MAC
    assert decoded.content.station_id == 42
    assert decoded.content.generation_delta_time_ms == tai_ms_from_unix_s(UNIX_S) % 65_536


def test_a_denm_yaml_gets_detection_and_reference_times_and_is_geo_broadcast_from_its_event(tmp_path):
    decoded = decode_packet(packet_from_send_file(load_send_file(write(tmp_path, "denm.yaml", DENM_YAML)), UNIX_S))
    assert decoded.message_type == ItsMessageId.DENM
    assert decoded.content.detection_time_tai_ms == decoded.content.reference_time_tai_ms == tai_ms_from_unix_s(UNIX_S)
    assert decoded.content.situation.event_type.cause_code == 3


@pytest.mark.parametrize("text, complaint", [
    ("type: spam\n", "type"),
    ("type: cam\ncontent: {speed: 3}\n", "speed"),
    ("type: cam\ngn: {source_mac: nope}\n", "nope"),
    ("type: [unclosed\n", "cam.yaml"),
])
def test_a_bad_send_file_is_an_error_naming_what_was_wrong(tmp_path, text, complaint):
    with pytest.raises(SendFileError) as error:
        packet_from_send_file(load_send_file(write(tmp_path, "cam.yaml", text)), UNIX_S)
    assert complaint in str(error.value)


def test_send_from_yaml_sends_one_datagram_to_the_address_and_port(tmp_path):
    with loopback_udp_socket(2.0) as receiver:
        assert send_from_yaml(write(tmp_path, "cam.yaml", CAM_YAML), *receiver.getsockname()) == ItsMessageId.CAM
        assert decode_packet(receiver.recv(4096)).station_id == 42


@pytest.fixture
def capture(tmp_path):
    path = tmp_path / "mixed.pcap"
    with open(path, "wb") as stream:
        writer = PcapWriter(stream, REMOTE_MAC)
        writer.write(cam_packet(remote_cam(0.0), 0.0), 1.0)
        writer.write(b"\x00\x01", 1.04)
    return path


def test_decode_capture_prints_one_line_per_packet_and_the_reason_of_an_undecodable_one(capture):
    lines = list(decode_capture(capture))
    assert "cam station 2002" in lines[0] and "02:00:00:00:00:2a" in lines[0] and "20.00 m/s" in lines[0]
    assert "ERROR truncated_basic_header" in lines[1]
    assert "errors: truncated_basic_header 1" in "\n".join(lines[2:])
    rejected = json.loads(list(decode_capture(capture, as_json=True))[1])
    assert rejected["error"] == "truncated_basic_header"


def test_decode_capture_reads_the_pcapng_tshark_writes(capture, tmp_path):
    converted = tmp_path / "mixed.pcapng"
    subprocess.run([tshark(), "-r", str(capture), "-F", "pcapng", "-w", str(converted)],
                   check=True, capture_output=True, timeout=60)
    records = [json.loads(line) for line in decode_capture(converted, as_json=True)][:-1]
    assert records[0]["station_id"] == 2002 and records[0]["time_s"] == pytest.approx(1.0)
    assert records[0]["content"]["station_type"] == its_pb2.StationType.Name(its_pb2.STATION_TYPE_PASSENGER_CAR)
