"""Wireshark's own dissector reads the pcap files we write (Debian package tshark)."""

import subprocess

import pytest

from coopdrive.v2x.packet import GnParams, SourcePosition, encode_cam, encode_denm
from coopdrive.recording.capture import read_capture
from coopdrive.v2x.pcap import PcapWriter
from coopdrive.v1 import its_pb2
from tests.system_packages import require

from .messages import denm

SOURCE_MAC = bytes.fromhex("02000000002a")


def tshark() -> str:
    """Path of tshark (Debian's package, installed before the suite by tools/system_packages.sh)."""
    return require("tshark")


def cam(station_id, latitude_deg, speed_mps, protocol_version):
    content = its_pb2.CamContent(protocol_version=protocol_version, station_id=station_id, station_type=5)
    content.reference_position.latitude_deg = latitude_deg
    content.reference_position.longitude_deg = 11.97
    content.high_frequency.speed_mps = speed_mps
    content.high_frequency.heading_rad = 0.0
    return content


@pytest.fixture(scope="module")
def capture(tmp_path_factory):
    path = tmp_path_factory.mktemp("pcap") / "v2x.pcap"
    with open(path, "wb") as stream:
        writer = PcapWriter(stream, SOURCE_MAC)
        writer.write(encode_cam(cam(1001, 57.7089, 22.22, 1), GnParams(source_mac=SOURCE_MAC, gn_version=0)), 1.0)
        writer.write(encode_cam(cam(1002, -33.5, 13.89, 2), GnParams(source_mac=SOURCE_MAC, gn_version=1)), 1.04)
        params = GnParams(source_mac=SOURCE_MAC, source_position=SourcePosition(51.45, 5.48))
        writer.write(encode_denm(denm(False, 1), params), 1.08)
    return path


def fields(path, *names):
    result = subprocess.run([tshark(), "-r", str(path), "-T", "fields", *sum([["-e", n] for n in names], [])],
                            check=True, capture_output=True, text=True, timeout=60)
    return [line.split("\t") for line in result.stdout.splitlines()]


def test_tshark_reads_station_id_latitude_and_speed_of_our_v1_and_v2_cams(capture):
    rows = fields(capture, "geonw.bh.version", "btpb.dstport", "its.stationID", "itsv1.latitude", "its.latitude",
                  "itsv1.speedValue", "its.speedValue")
    assert rows[0] == ["0", "2001", "1001", "577089000", "", "2222", ""]
    assert rows[1] == ["1", "2001", "1002", "", "-335000000", "", "1389"]


def test_tshark_reads_our_denm_on_port_2002(capture):
    rows = fields(capture, "btpb.dstport", "its.messageID", "itsv1.originatingStationID")
    assert rows[2] == ["2002", "1", "0"]


def test_tshark_finds_no_malformed_packet_in_our_capture(capture):
    assert all(row == [""] for row in fields(capture, "_ws.malformed"))


def test_our_reader_reads_the_pcapng_tshark_writes_from_our_capture(capture, tmp_path):
    converted = tmp_path / "v2x.pcapng"
    subprocess.run([tshark(), "-r", str(capture), "-F", "pcapng", "-w", str(converted)],
                   check=True, capture_output=True, timeout=60)
    frames = list(read_capture(converted))
    assert [frame.time_s for frame in frames] == pytest.approx([1.0, 1.04, 1.08])
    assert frames[0].source_mac == SOURCE_MAC
