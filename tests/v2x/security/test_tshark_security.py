"""Wireshark's ieee1609dot2 dissector reads our signed packets, and our capture report verifies them."""

import subprocess

import pytest

from coopdrive.v2x.pcap import PcapWriter
from coopdrive.v2x.reasons import RejectReason
from coopdrive.services.v2x.capture_decode import CaptureDecoder
from coopdrive.v2x.security.pki import tamper_packet
from coopdrive.v2x.timebase import unix_s_from_tai_ms

from ..test_tshark import tshark
from .signed import cam_packet, denm_packet, iclcm_packet, now_tai_us

US_PER_MS = 1000
STEP_US = 100_000
# frame: (vehicle, message, GN version, tampered); vehicle a sends a CAM with its certificate first.
FRAMES = [("a", cam_packet, 1, False), ("a", cam_packet, 1, False), ("a", denm_packet, 1, False),
          ("a", iclcm_packet, 1, False), ("b", cam_packet, 0, False), ("a", cam_packet, 1, True)]


@pytest.fixture(scope="module")
def capture(pki, tmp_path_factory):
    path = tmp_path_factory.mktemp("pcap") / "signed.pcap"
    signers = {name: pki.signer(name) for name in ("a", "b")}
    start = now_tai_us()
    with open(path, "wb") as stream:
        writer = PcapWriter(stream, bytes.fromhex("02000000002a"))
        for index, (vehicle, make, gn_version, tampered) in enumerate(FRAMES):
            signer, now = signers[vehicle], start + index * STEP_US
            unsecured = make(signer, gn_version) if make is cam_packet else make(signer)
            packet = signer.sign(unsecured, now)
            writer.write(tamper_packet(packet) if tampered else packet, unix_s_from_tai_ms(now // US_PER_MS))
    return path, signers


def fields(path, *names):
    result = subprocess.run([tshark(), "-r", str(path), "-T", "fields", *sum([["-e", n] for n in names], [])],
                            check=True, capture_output=True, text=True, timeout=60)
    return [line.split("\t") for line in result.stdout.splitlines()]


def test_tshark_dissects_every_signed_packet_with_an_ieee1609dot2_layer_and_nothing_malformed(capture):
    path, signers = capture
    rows = fields(path, "frame.protocols", "_ws.malformed", "ieee1609dot2.psid", "btpb.dstport", "its.stationID")
    assert len(rows) == len(FRAMES)
    assert all(":gnw:ieee1609dot2" in row[0] and row[1] == "" for row in rows)
    # a full certificate lists its permissions (36, 37, 127) after the data's own PSID
    assert [row[2].split(",")[0] for row in rows] == ["36", "36", "37", "127", "36", "36"]
    assert rows[0][3:] == ["2001", str(signers["a"].station_id)]
    assert rows[4][3:] == ["2001", str(signers["b"].station_id)]


def test_tshark_sees_the_certificate_once_then_the_digest_we_verify_against(capture):
    path, signers = capture
    digests = [row[0] for row in fields(path, "ieee1609dot2.digest")]
    assert digests[1] == signers["a"].identity.ticket.digest.hex()


def test_our_report_of_the_capture_says_who_signed_each_packet_and_that_only_the_tampered_one_fails(capture, pki):
    path, signers = capture
    rows = list(CaptureDecoder(pki.store(), freshness=False).records(path))
    assert [row["message_type"] for row in rows] == ["cam", "cam", "denm", "iclcm", "cam", "cam"]
    security = [row["security"] for row in rows]
    assert all(row["signed"] for row in security)
    assert [row["signer"] for row in security] == ["certificate", "digest"] * 3
    assert [row["signer_digest"] for row in security][:2] == [signers["a"].identity.ticket.digest.hex()] * 2
    assert [row["verified"] for row in security] == [True, True, True, True, True, False]
    assert [row["trusted"] for row in security][:5] == [True] * 5
    assert security[-1]["reason"] == RejectReason.INVALID_SIGNATURE.value


def test_the_report_reads_the_pcapng_tshark_writes_and_without_roots_verifies_but_trusts_nothing(capture, tmp_path):
    path, signers = capture
    converted = tmp_path / "signed.pcapng"
    subprocess.run([tshark(), "-r", str(path), "-F", "pcapng", "-w", str(converted)],
                   check=True, capture_output=True, timeout=60)
    security = [row["security"] for row in CaptureDecoder(freshness=False).records(converted)]
    assert [row["verified"] for row in security] == [True, True, True, True, True, False]
    assert [row["trusted"] for row in security] == [None] * len(FRAMES)
    assert security[4]["signer_digest"] == signers["b"].identity.ticket.digest.hex()
