"""TS 103 097 v1.2.1 secured packets (GN version 0, as GCDC-era roadside units send them): decoded and verified
as `coopdrive v2x decode` and the receive path see them, from test vectors written from the standard
(v121_vectors.py) with keys of our own."""

import json
import time

import pytest

from coopdrive.services.v2x.capture_decode import CaptureDecoder, decode_capture
from coopdrive.v2x.geonet import BASIC_HEADER_SIZE
from coopdrive.v2x.packet import V2xPacketCodec
from coopdrive.v2x.pcap import PcapWriter
from coopdrive.v2x.reasons import V2xDecodeError
from coopdrive.v2x.security.inspection import PacketInspector
from coopdrive.v2x.security.layer import ModeSecurityLayer
from coopdrive.v2x.security.pki import create_test_pki
from coopdrive.v2x.security.profile import PSID_DENM, SecurityMode
from coopdrive.v2x.security.store import CertificateStore
from coopdrive.v2x.security.v121_reader import EccPointType, PayloadType, PresentationReader, encode_length
from coopdrive.v2x.security.verifier import SecurityVerifier
from coopdrive.v2x.timebase import tai_ms_from_unix_s

from .signed import CODEC, cam, gn_params
from .v121_vectors import SUBJECT_AUTHORIZATION_AUTHORITY, Signer, V121Key, secure

SOURCE_MAC = b"\x02\x00\x00\x00\x12\x01"
STATION_ID = 1201
US_PER_MS = 1000
CAPTURE_TIME_S = 1_700_000_000.0
SPEED_MPS = 22.2


class _Station:
    mac = SOURCE_MAC
    station_id = STATION_ID


def gn_v0_cam() -> bytes:
    return CODEC.encode_cam(cam(STATION_ID, SPEED_MPS), gn_params(_Station, gn_version=0))


def generation_time_us(unix_s: float = CAPTURE_TIME_S) -> int:
    return tai_ms_from_unix_s(unix_s) * US_PER_MS


@pytest.fixture(scope="module")
def ticket():
    authority = V121Key.generate()
    authority.issue(authority, subject_type=SUBJECT_AUTHORIZATION_AUTHORITY)
    return authority.issue(V121Key.generate())


def records_of(tmp_path, packets: list[bytes]) -> list[dict]:
    path = tmp_path / "v121.pcap"
    with open(path, "wb") as stream:
        writer = PcapWriter(stream, SOURCE_MAC)
        for packet in packets:
            writer.write(packet, CAPTURE_TIME_S)
    return list(CaptureDecoder().records(path))


@pytest.mark.parametrize("value, encoded", [(0, "00"), (36, "24"), (127, "7f"), (141, "808d"), (16383, "bfff"),
                                            (16384, "c04000")])
def test_the_variable_length_code_of_clause_4_1_reads_what_it_writes(value, encoded):
    assert encode_length(value).hex() == encoded
    assert PresentationReader(bytes.fromhex(encoded)).length() == value


def test_a_gn_v0_cam_signed_with_its_certificate_decodes_and_verifies_in_v2x_decode_json(tmp_path, ticket):
    packet = secure(gn_v0_cam(), ticket, Signer.CERTIFICATE, generation_time_us())
    path = tmp_path / "v121.pcap"
    with open(path, "wb") as stream:
        PcapWriter(stream, SOURCE_MAC).write(packet, CAPTURE_TIME_S)
    record = json.loads(next(decode_capture(path, as_json=True)))
    assert record["security"] == {"signed": True, "signer": "certificate", "signer_digest": ticket.digest.hex(),
                                  "verified": True, "fresh": True, "trusted": None, "reason": None, "psid": 36,
                                  "generation_time_us": generation_time_us()}
    assert (record["gn"]["version"], record["message_type"], record["station_id"]) == (0, "cam", STATION_ID)
    assert record["content"]["high_frequency"]["speed_mps"] == pytest.approx(SPEED_MPS)


def test_a_digest_signer_resolves_from_the_certificate_of_an_earlier_packet(tmp_path, ticket):
    first = secure(gn_v0_cam(), ticket, Signer.CERTIFICATE, generation_time_us())
    later = secure(gn_v0_cam(), ticket, Signer.DIGEST, generation_time_us())
    alone, after = records_of(tmp_path, [later])[0], records_of(tmp_path, [first, later])[1]
    assert (alone["security"]["verified"], alone["security"]["reason"]) == (None, "unknown_signer_digest")
    assert alone["security"]["signer_digest"] == ticket.digest.hex()
    assert alone["content"]["high_frequency"]["speed_mps"] == pytest.approx(SPEED_MPS)
    assert (after["security"]["signer"], after["security"]["verified"], after["security"]["reason"]) == \
        ("digest", True, None)


@pytest.mark.parametrize("offset_from_end", [1, 40, 80])
def test_a_flipped_byte_fails_verification_and_the_content_is_still_shown(tmp_path, ticket, offset_from_end):
    """The last byte of s, a byte of R, a byte of the signed CAM itself (before the 69-byte trailer)."""
    packet = bytearray(secure(gn_v0_cam(), ticket, Signer.CERTIFICATE, generation_time_us()))
    packet[-offset_from_end] ^= 0x01
    (record,) = records_of(tmp_path, [bytes(packet)])
    assert (record["security"]["verified"], record["security"]["reason"]) == (False, "invalid_signature")
    assert record["station_id"] == STATION_ID and record["message_type"] == "cam"


@pytest.mark.parametrize("r_form", list(EccPointType))
@pytest.mark.parametrize("key_form", [EccPointType.COMPRESSED_LSB_Y_0, EccPointType.UNCOMPRESSED])
def test_every_form_of_r_and_of_the_verification_key_verifies(r_form, key_form):
    authority = V121Key.generate()
    authority.issue(authority, subject_type=SUBJECT_AUTHORIZATION_AUTHORITY)
    ticket = authority.issue(V121Key.generate(), key_form=key_form, r_form=r_form)
    packet = secure(gn_v0_cam(), ticket, Signer.CERTIFICATE, generation_time_us(), r_form=r_form)
    security = PacketInspector(CertificateStore()).inspect(packet).security
    assert (security.verified, security.signer_digest) == (True, ticket.digest)


def test_a_certificate_chain_signer_verifies_with_its_last_certificate_and_is_remembered(ticket):
    authority = V121Key.generate()
    authority_certificate = authority.issue(authority, subject_type=SUBJECT_AUTHORIZATION_AUTHORITY)
    chained = authority.issue(V121Key.generate())
    inspector = PacketInspector(CertificateStore())
    chain_packet = secure(gn_v0_cam(), chained, Signer.CHAIN, generation_time_us(),
                          chain=(authority_certificate.encoded,))
    assert inspector.inspect(chain_packet).security.signer == "certificate_chain"
    assert inspector.inspect(chain_packet).security.verified is True
    digest_packet = secure(gn_v0_cam(), chained, Signer.DIGEST, generation_time_us())
    assert inspector.inspect(digest_packet).security.verified is True


def test_an_its_aid_for_another_service_than_the_btp_port_fails_verification(ticket):
    packet = secure(gn_v0_cam(), ticket, Signer.CERTIFICATE, generation_time_us(), psid=PSID_DENM)
    security = PacketInspector(CertificateStore()).inspect(packet).security
    assert (security.verified, security.reason.value) == (False, "psid_port_mismatch")


def test_an_encrypted_payload_is_refused_as_unsupported_content(ticket):
    packet = secure(gn_v0_cam(), ticket, Signer.CERTIFICATE, generation_time_us(), payload_type=PayloadType.ENCRYPTED)
    inspected = PacketInspector(CertificateStore()).inspect(packet)
    assert inspected.unsecured_packet is None
    assert (inspected.security.verified, inspected.security.reason.value) == (False, "unsupported_secured_content")


def test_the_receive_path_verifies_v121_packets_and_trusts_none_of_them_against_our_roots(tmp_path, ticket):
    now_s = time.time()
    packet = secure(gn_v0_cam(), ticket, Signer.CERTIFICATE, generation_time_us(now_s))
    pki = create_test_pki(tmp_path, ["ego"])
    clock = lambda: generation_time_us(now_s)  # noqa: E731 -- the layer's clock, pinned to the packet's time
    checking = ModeSecurityLayer(SecurityMode.SIGN_AND_VERIFY, SecurityVerifier(pki.store()), pki.signer("ego"), clock)
    decoded = V2xPacketCodec(security=checking).decode_packet(packet)
    assert (decoded.security.verified, decoded.security.fresh, decoded.security.trusted) == (True, True, False)
    assert decoded.security.reason.value == "unknown_issuer"
    assert decoded.content.high_frequency.speed_mps == pytest.approx(SPEED_MPS)
    requiring = ModeSecurityLayer(SecurityMode.VERIFY_REQUIRED, SecurityVerifier(pki.store()), pki.signer("ego"), clock)
    with pytest.raises(V2xDecodeError) as refused:
        V2xPacketCodec(security=requiring).decode_packet(packet)
    assert refused.value.reason.value == "untrusted"


def test_a_refused_v121_packet_is_still_read_for_its_sender(ticket):
    packet = secure(gn_v0_cam(), ticket, Signer.DIGEST, generation_time_us())
    opened = SecurityVerifier(CertificateStore()).unwrap(packet, count=False)
    assert opened.unsecured_packet[BASIC_HEADER_SIZE:] == gn_v0_cam()[BASIC_HEADER_SIZE:]
    assert opened.result.signer_digest == ticket.digest
