"""`coopdrive pki init` and `coopdrive v2x decode` as a user runs them."""

import json
import subprocess
import sys
import time

from coopdrive.v2x.packet import GnParams, SourcePosition, V2xPacketCodec
from coopdrive.v2x.pcap import PcapWriter
from coopdrive.v2x.security.pki import load_test_pki, tamper_packet
from coopdrive.v2x.timebase import tai_ms_from_unix_s, unix_s_from_tai_ms
from coopdrive.v1 import its_pb2

US_PER_MS = 1000


def now_tai_us() -> int:
    return tai_ms_from_unix_s(time.time()) * US_PER_MS


def cam_packet(signer) -> bytes:
    content = its_pb2.CamContent(protocol_version=1, station_id=signer.station_id, station_type=5)
    content.reference_position.latitude_deg = 51.4758
    content.reference_position.longitude_deg = 5.6247
    content.high_frequency.speed_mps = 22.0
    content.high_frequency.heading_rad = 0.2
    params = GnParams(source_mac=signer.mac, gn_version=1, source_position=SourcePosition(51.4758, 5.6247, 22.0, 0.2))
    return V2xPacketCodec().encode_cam(content, params)


def coopdrive(*args):
    return subprocess.run([sys.executable, "-m", "coopdrive.cli", *args], capture_output=True, text=True, timeout=120)


def test_pki_init_writes_a_pki_and_refuses_to_overwrite_it(tmp_path):
    first = coopdrive("pki", "init", str(tmp_path / "pki"), "--vehicles", "car1", "car2")
    assert first.returncode == 0, first.stderr
    assert set(load_test_pki(tmp_path / "pki").tickets) == {"car1", "car2"}
    again = coopdrive("pki", "init", str(tmp_path / "pki"))
    assert again.returncode == 1 and "not overwriting" in again.stderr


def test_decode_shows_who_signed_each_cam_and_whether_it_verified(tmp_path):
    assert coopdrive("pki", "init", str(tmp_path / "pki"), "--vehicles", "car1").returncode == 0
    signer = load_test_pki(tmp_path / "pki").signer("car1")
    capture = tmp_path / "signed.pcap"
    start = now_tai_us()
    with open(capture, "wb") as stream:
        writer = PcapWriter(stream, bytes.fromhex("02000000002a"))
        for index in range(3):
            now = start + index * 40_000
            packet = signer.sign(cam_packet(signer), now)
            writer.write(tamper_packet(packet) if index == 2 else packet, unix_s_from_tai_ms(now // US_PER_MS))
    result = coopdrive("v2x", "decode", str(capture), "--json", "--trust", str(tmp_path / "pki"))
    assert result.returncode == 0, result.stderr
    reports = [json.loads(line)["security"] for line in result.stdout.splitlines()[:-1]]
    assert [r["verified"] for r in reports] == [True, True, False] and [r["trusted"] for r in reports][:2] == [True] * 2
    assert reports[2]["reason"] == "invalid_signature"
    assert len({r["signer_digest"] for r in reports}) == 1
    assert json.loads(result.stdout.splitlines()[-1])["summary"]["signatures"] == {"verified": 2, "invalid": 1}


def test_decode_of_a_file_that_is_no_capture_fails_with_its_name(tmp_path):
    bogus = tmp_path / "notes.pcap"
    bogus.write_bytes(b"not a capture at all")
    result = coopdrive("v2x", "decode", str(bogus))
    assert result.returncode == 2
    assert "notes.pcap" in result.stderr


def test_decode_with_a_trust_file_that_is_no_certificate_fails_naming_it(tmp_path):
    capture = tmp_path / "empty.pcap"
    with open(capture, "wb") as stream:
        PcapWriter(stream, bytes.fromhex("02000000002a"))
    (tmp_path / "root.cert").write_bytes(b"not a certificate")
    result = coopdrive("v2x", "decode", str(capture), "--trust", str(tmp_path / "root.cert"))
    assert result.returncode == 2
    assert "root.cert: not a COER certificate" in result.stderr
