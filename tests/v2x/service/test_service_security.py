"""The V2xService with the TS 103 097 security layer over real UDP on 127.0.0.1, through a fake radio box."""

import random
import time
from datetime import datetime, timezone

import dpkt
import pytest
from pydantic import ValidationError

from coopdrive.v2x.geonet import BASIC_HEADER_SIZE
from coopdrive.v2x.packet import decode_packet
from coopdrive.v2x.reasons import RejectReason
from coopdrive.v2x.security.profile import SecurityMode
from coopdrive.v2x.security.run_setup import security_overrides
from coopdrive.services.v2x.service import V2xService
from coopdrive.v1 import ego_pb2, v2x_pb2

from .streams import REMOTE_STATION_ID, cam_packet, remote_cam
from .test_service_udp import WAIT_S, radio, start_service  # noqa: F401  (fixtures)

START_S = 10.0
# Sim time START_S is half an hour before the wall clock: inside the tickets' validity (they start an hour
# back), far outside the 2 s freshness window, so verification passes only on the service's ITS clock.
SIM_BEHIND_WALL_S = 1800.0
BITS_PER_BYTE = 8
SEED = 103097
FLIPPED_BITS_SAMPLED = 120
STATIONS = {"a": (1101, "02:00:00:00:11:01"), "b": (1102, "02:00:00:00:11:02"), "rogue": (1103, "02:00:00:00:11:03")}


@pytest.fixture(scope="module")
def overrides(tmp_path_factory):
    return security_overrides(tmp_path_factory.mktemp("run") / "pki", list(STATIONS),
                              SecurityMode.VERIFY_REQUIRED, untrusted=["rogue"])


def epoch_utc() -> str:
    return datetime.fromtimestamp(time.time() - SIM_BEHIND_WALL_S - START_S, timezone.utc).isoformat()


@pytest.fixture
def station(start_service, overrides):  # noqa: F811
    epoch = epoch_utc()

    def start(name: str, **extra):
        station_id, mac = STATIONS[name]
        return start_service(START_S, station_id=station_id, vehicle_mac=mac, clock_epoch_utc=epoch,
                             send_iclcm=False, **{"pcap_path": None, **overrides[name], **extra})

    return start


def sent_cam(service, ctx, radio) -> bytes:  # noqa: F811
    ctx.deliver("ego/state", ego_pb2.EgoState(x_m=5.0, y_m=2.0, heading_rad=0.2, speed_mps=15.0))
    service.transmit(ctx.now_s())
    packet, _ = radio.recvfrom(4096)
    return packet


def deliver(service, ctx, radio, *packets: bytes) -> None:  # noqa: F811
    for packet in packets:
        radio.sendto(packet, service.link.local_address)
    ctx.pump(len(packets))
    service.flush_received(ctx.now_s())
    service.publish_status(ctx.now_s())


def rejected(ctx) -> dict[str, int]:
    return dict(ctx.messages("v2x/status")[-1].rejected_by_reason)


def test_two_stations_in_verify_required_with_tickets_of_one_pki_hear_each_others_signed_cams(station, radio):  # noqa: F811
    (a, a_ctx), (b, b_ctx) = station("a"), station("b")
    from_a, from_b = sent_cam(a, a_ctx, radio), sent_cam(b, b_ctx, radio)
    security = decode_packet(from_a).security  # really signed: a codec without roots verifies, cannot trust
    assert (security.signed, security.verified, security.trusted) == (True, True, None)
    deliver(b, b_ctx, radio, from_a)
    deliver(a, a_ctx, radio, from_b)
    assert [cam.station_id for cam in b_ctx.messages("v2x/cam")] == [STATIONS["a"][0]]
    assert [cam.station_id for cam in a_ctx.messages("v2x/cam")] == [STATIONS["b"][0]]
    assert rejected(a_ctx) == rejected(b_ctx) == {}
    assert b.counters["security_verified"] == 1
    [a_stats] = b_ctx.messages("v2x/status")[-1].stations
    assert (a_stats.signed, a_stats.verified, a_stats.trusted, a_stats.last_security_reason) == (True, True, True, "")
    assert (a_stats.messages_signed, a_stats.messages_verified, a_stats.messages_trusted) == (1, 1, 1)


def test_a_station_with_an_untrusted_ticket_is_dropped_with_its_reason_counted(station, radio):  # noqa: F811
    (rogue, rogue_ctx), (b, b_ctx) = station("rogue"), station("b")
    deliver(b, b_ctx, radio, sent_cam(rogue, rogue_ctx, radio))
    assert b_ctx.messages("v2x/cam") == []
    # its signature is valid (the ticket travels with it), but the ticket's issuer chains to no root b trusts
    assert rejected(b_ctx) == {RejectReason.UNTRUSTED.value: 1}
    assert b.counters[f"rejected_{RejectReason.UNTRUSTED.value}"] == 1
    # listed, never heard: refused by the security mode, signed by a signer nobody trusts
    [rogue_stats] = b_ctx.messages("v2x/status")[-1].stations
    assert (rogue_stats.station_id, rogue_stats.state) == (STATIONS["rogue"][0], v2x_pb2.LINK_STATE_LOST)
    assert (rogue_stats.messages_signed, rogue_stats.messages_refused_by_security, rogue_stats.messages_trusted,
            rogue_stats.messages_untrusted) == (1, 1, 0, 1)
    assert (rogue_stats.signed, rogue_stats.trusted, rogue_stats.messages_received) == (True, False, 0)
    assert rogue_stats.last_security_reason == RejectReason.UNTRUSTED.value


def test_the_station_with_the_untrusted_ticket_still_hears_and_verifies_the_others(station, radio):  # noqa: F811
    (rogue, rogue_ctx), (b, b_ctx) = station("rogue"), station("b")
    deliver(rogue, rogue_ctx, radio, sent_cam(b, b_ctx, radio))
    assert [cam.station_id for cam in rogue_ctx.messages("v2x/cam")] == [STATIONS["b"][0]]
    assert rogue.counters["security_verified"] == 1


def test_verify_required_refuses_an_unsigned_cam_with_its_reason_counted(station, radio):  # noqa: F811
    b, b_ctx = station("b")
    deliver(b, b_ctx, radio, cam_packet(remote_cam(START_S, clock=b.clock), START_S, clock=b.clock))
    assert b_ctx.messages("v2x/cam") == []
    assert rejected(b_ctx) == {RejectReason.UNSECURED_PACKET_REFUSED.value: 1}


def test_every_sampled_single_bit_flip_of_a_signed_cam_is_rejected_with_a_counted_reason(station, radio):  # noqa: F811
    (a, a_ctx), (b, b_ctx) = station("a"), station("b")
    packet = sent_cam(a, a_ctx, radio)
    secured_bits = range(BASIC_HEADER_SIZE * BITS_PER_BYTE, len(packet) * BITS_PER_BYTE)
    bits = random.Random(SEED).sample(secured_bits, FLIPPED_BITS_SAMPLED)
    flipped = []
    for bit in bits:
        changed = bytearray(packet)
        changed[bit // BITS_PER_BYTE] ^= 0x80 >> (bit % BITS_PER_BYTE)
        flipped.append(bytes(changed))
    deliver(b, b_ctx, radio, *flipped)
    assert b_ctx.messages("v2x/cam") == []
    counts = rejected(b_ctx)
    assert sum(counts.values()) == FLIPPED_BITS_SAMPLED
    assert set(counts) <= {reason.value for reason in RejectReason}
    assert RejectReason.INVALID_SIGNATURE.value in counts
    # the flips that left the sender readable count against station a, invalid signatures among them
    [a_stats] = b_ctx.messages("v2x/status")[-1].stations
    assert a_stats.station_id == STATIONS["a"][0] and 0 < a_stats.signature_failures <= counts["invalid_signature"]
    assert 0 < a_stats.messages_refused_by_security <= FLIPPED_BITS_SAMPLED
    # the untouched packet still passes afterwards: the forgeries spoiled nothing
    deliver(b, b_ctx, radio, packet)
    assert [cam.station_id for cam in b_ctx.messages("v2x/cam")] == [STATIONS["a"][0]]


def test_mode_off_sends_and_accepts_todays_unsigned_packets(start_service, radio):  # noqa: F811
    service, ctx = start_service(START_S, clock_epoch_utc="2016-05-28T10:00:00Z", pcap_path=None,
                                 send_iclcm=False)
    assert service.security is None
    assert decode_packet(sent_cam(service, ctx, radio)).station_id == service.config.station_id
    deliver(service, ctx, radio, cam_packet(remote_cam(START_S), START_S))
    assert [cam.station_id for cam in ctx.messages("v2x/cam")] == [REMOTE_STATION_ID]


def test_mode_off_without_a_pki_sends_unsigned_and_hears_signed_cams(station, radio):  # noqa: F811
    (a, a_ctx), (b, b_ctx) = station("a"), station("b", security={"mode": "off", "pki_dir": None})
    assert decode_packet(sent_cam(b, b_ctx, radio)).station_id == STATIONS["b"][0]
    deliver(b, b_ctx, radio, sent_cam(a, a_ctx, radio))
    assert [cam.station_id for cam in b_ctx.messages("v2x/cam")] == [STATIONS["a"][0]]  # real cars are heard
    assert rejected(b_ctx) == {}


@pytest.mark.parametrize("security, key", [
    ({"mode": "verify_required"}, "security.pki_dir"),
    ({"mode": "sign_only", "pki_dir": "PKI"}, "security.ticket"),
    ({"mode": "verify_required", "pki_dir": "PKI", "ticket": "nobody"}, "security.ticket 'nobody'"),
    ({"mode": "verify_required", "pki_dir": "PKI/vehicles"}, "security.pki_dir"),
    ({"mode": "verify_required", "pki_dir": "PKI", "ticket": "a", "extra_trusted_roots": ["PKI/none"]},
     "security.extra_trusted_roots"),
])
def test_a_security_config_error_names_the_key(overrides, security, key):
    pki_dir = overrides["a"]["security"]["pki_dir"]
    security = {name: value.replace("PKI", pki_dir) if isinstance(value, str) else
                [item.replace("PKI", pki_dir) for item in value] if isinstance(value, list) else value
                for name, value in security.items()}
    with pytest.raises(ValidationError, match=key):
        V2xService.Config.model_validate({"security": security})


def test_a_received_signed_cam_keeps_its_sender_s_mac_in_our_pcap(station, radio, tmp_path):  # noqa: F811
    (a, a_ctx), (b, b_ctx) = station("a"), station("b", pcap_path=str(tmp_path / "b.pcap"))
    deliver(b, b_ctx, radio, sent_cam(a, a_ctx, radio))
    b.stop()
    with open(tmp_path / "b.pcap", "rb") as stream:
        [(_, frame)] = dpkt.pcap.Reader(stream)
    assert bytes(dpkt.ethernet.Ethernet(frame).src) == bytes.fromhex(STATIONS["a"][1].replace(":", ""))
