"""Mutated real packets through the v2x service's whole receive path: security envelope, decoder, plausibility,
station table, status, pcap and bus hand-over (V2xService.on_datagram, flush_received, publish_status).

Seeds: every GN packet of the three real captures in shared/data/v2x (signed CAMs and a SPATEM from the road,
ms-van3t CAMs and CPMs, FlexStack CAMs, VAMs and beacons) and our own CAM, DENM and iCLCM, unsigned and signed
with a test PKI ticket. The CI test runs FUZZ_TEST_PACKETS of them; the full run is

    .venv/bin/python -m tests.v2x.service.receive_fuzz --packets 100000
"""

from __future__ import annotations

import argparse
import gc
import random
import socket
import tempfile
import time
from collections import Counter
from collections.abc import Callable
from dataclasses import dataclass, field
from pathlib import Path

from coopdrive.v2x.reasons import V2xDecodeError
from coopdrive.recording.capture import read_gn_packets
from coopdrive.runtime.testing import MemoryContext
from coopdrive.v2x.infrastructure import InfrastructureCodec
from coopdrive.v2x.release2 import release2_spec
from coopdrive.v2x.security.pki import create_test_pki, tamper_packet
from coopdrive.v2x.geonet import is_secured
from coopdrive.services.v2x.service import V2xService
from coopdrive.v2x.timebase import generation_delta_time_ms, tai_ms_from_unix_s
from tests.shared_data import shared_file
from tests.v2x.security.signed import CODEC, cam, denm_packet, gn_params, iclcm_packet
from tests.v2x.test_fuzz import mutate as mutate_gn, seeds as unsigned_seeds
from tests.v2x.udp_socket import loopback_udp_socket

CAPTURES = ("v2x/considerit_signed_testvectors.pcap", "v2x/msvan3t_cam_cpm_trace.pcapng",
            "v2x/flexstack_cam_vam_beacons.pcap")
# Real packets taken from each capture (the ms-van3t trace holds 929 alike).
PER_CAPTURE = 60
SEED = 25
# Service time per packet: 100 000 packets span 20 s, so stations come, go LOST and are forgotten.
STEP_S = 0.0002
FLUSH_EVERY = 500
US_PER_MS = 1000
# test_fuzz.mutate edits fixed offsets up to here (BTP port, ITS header of an SHB packet).
MUTATE_GN_MIN_BYTES = 48
TAMPER_SHARE = 0.25
# Bits counted from the end of the signed facility message (tamper_packet).
TAMPER_BITS = 64
# CPU time of one packet above which the receive path is taken to stall.
SLOWEST_PACKET_CPU_S = 0.1


@dataclass
class FuzzOutcome:
    packets: int = 0
    accepted: int = 0
    own: int = 0
    # GN beacons: no message to deliver, nor a rejection; they update the neighbour's position.
    beacons: int = 0
    rejected: Counter = field(default_factory=Counter)
    # CPU time of this thread: the machine may be shared, a stall shows as CPU spent (or as no end at all).
    slowest_packet_cpu_s: float = 0.0
    cpu_s: float = 0.0
    elapsed_s: float = 0.0
    stations_listed_max: int = 0
    # The security layer's own counts (sign_and_verify delivers a packet that failed, marked): security_<reason>.
    security: dict = field(default_factory=dict)
    # What was delivered, by kind: received_cam, received_spatem...
    received: dict = field(default_factory=dict)


def real_seeds() -> list[bytes]:
    packets = []
    for name in CAPTURES:
        packets += [packet.gn_packet for packet in read_gn_packets(shared_file(name))][:PER_CAPTURE]
    return packets


def signed_seeds(pki_dir: Path, now_s: float) -> list[bytes]:
    """A fresh CAM (generated now), a DENM and an iCLCM of one station, signed: the first with its full
    certificate, the others with its digest."""
    pki = create_test_pki(pki_dir, ["fuzzer", "ego"])
    signer = pki.signer("fuzzer", 4242)
    now_tai_ms = tai_ms_from_unix_s(now_s)
    content = cam(signer.station_id)
    content.generation_delta_time_ms = generation_delta_time_ms(now_tai_ms)
    fresh_cam = CODEC.encode_cam(content, gn_params(signer))
    return [signer.sign(packet, now_tai_ms * US_PER_MS)
            for packet in (fresh_cam, denm_packet(signer), iclcm_packet(signer), fresh_cam)]


Mutation = Callable[[random.Random, bytes], bytes]


def mutate(rng: random.Random, packet: bytes) -> bytes:
    """test_fuzz's mutations; a packet too short for its fixed offsets (a beacon) gets bit flips or a cut; one
    secured packet in four has one bit of its signed message flipped (a forgery the signature must catch)."""
    if is_secured(packet) and rng.random() < TAMPER_SHARE:
        try:
            return tamper_packet(packet, rng.randrange(TAMPER_BITS))
        except V2xDecodeError:
            pass
    if len(packet) >= MUTATE_GN_MIN_BYTES:
        try:
            return mutate_gn(rng, packet)
        except V2xDecodeError:
            pass  # its "random ASN.1 behind valid headers" rebuilds the GN packet: not for secured ones
    data = bytearray(packet)
    if rng.random() < 0.5:
        return bytes(data[:rng.randrange(len(data))])
    for _ in range(rng.randint(1, 4)):
        data[rng.randrange(len(data))] ^= 1 << rng.randrange(8)
    return bytes(data)


def signing_with(pki_dir: Path) -> dict:
    """The security block of a service that signs and verifies with pki_dir's ticket `ego`."""
    return {"mode": "sign_and_verify", "pki_dir": str(pki_dir), "ticket": "ego"}


def start_service(pcap_path: Path, now_s: float, security: dict | None = None
                  ) -> tuple[V2xService, MemoryContext, socket.socket]:
    """A v2x service on a loopback radio, its clock at now_s; security: the config's block (None: off)."""
    # The roadside and road-user modules are compiled once per process, on the first such packet: compiled here, a
    # packet's time is its own work (a mutated port makes any packet one of theirs).
    InfrastructureCodec.spec()
    release2_spec()
    radio = loopback_udp_socket()
    ctx = MemoryContext(queue_calls=True, opens_hardware=True)
    ctx.clock.set(now_s)
    config = {"link": {"radio_port": radio.getsockname()[1], "listen_port": 0}, "station_id": 1001,
              "vehicle_mac": "02:00:00:00:10:01", "pcap_path": str(pcap_path), "send_iclcm": False}
    if security is not None:
        config["security"] = security
    service = V2xService(V2xService.Config.model_validate(config), ctx)
    service.start()
    return service, ctx, radio


def _feed(service: V2xService, ctx: MemoryContext, groups: list[list[bytes]], packets: int, rng: random.Random,
          outcome: FuzzOutcome, mutation: Mutation) -> None:
    started, started_cpu = time.perf_counter(), time.thread_time()
    for index in range(packets):
        original = rng.choice(rng.choice(groups))
        data = original if rng.random() < 0.05 else mutation(rng, original)
        before = time.thread_time()
        service.on_datagram(data)
        outcome.slowest_packet_cpu_s = max(outcome.slowest_packet_cpu_s, time.thread_time() - before)
        ctx.clock.set(ctx.now_s() + STEP_S)
        if index % FLUSH_EVERY == FLUSH_EVERY - 1:
            _flush(service, ctx, outcome)
    _flush(service, ctx, outcome)
    outcome.elapsed_s, outcome.cpu_s = time.perf_counter() - started, time.thread_time() - started_cpu


def fuzz(service: V2xService, ctx: MemoryContext, groups: list[list[bytes]], packets: int,
         seed: int = SEED, mutation: Mutation = mutate) -> FuzzOutcome:
    """Each packet a mutation (or, one time in twenty, the original) of a seed of a group drawn evenly."""
    rng = random.Random(seed)
    outcome = FuzzOutcome()
    # A packet's time is its own work and the garbage it makes, not a full collection of whatever the process
    # held before (a test suite's heap made one packet 0.29 s in CI): what exists now is left out of collections.
    gc.collect()
    gc.freeze()
    try:
        _feed(service, ctx, groups, packets, rng, outcome, mutation)
    finally:
        gc.unfreeze()
    reception = service.reception
    outcome.packets, outcome.own = reception.packets_received, reception.own_packets_ignored
    outcome.beacons = reception.beacons_received
    outcome.rejected = Counter(reception.rejected_by_reason)
    outcome.received = {name: count for name, count in service.counters.items() if name.startswith("received_")}
    outcome.accepted = sum(outcome.received.values())
    outcome.security = {name: count for name, count in service.counters.items() if name.startswith("security_")}
    return outcome


def _flush(service: V2xService, ctx: MemoryContext, outcome: FuzzOutcome) -> None:
    service.flush_received(ctx.now_s())
    service.publish_status(ctx.now_s())
    status = ctx.messages("v2x/status")[-1]
    outcome.stations_listed_max = max(outcome.stations_listed_max, len(status.stations))
    ctx.outputs.clear()


def run_in_service(folder: Path, now_s: float, groups: list[list[bytes]], packets: int,
                   mutation: Mutation = mutate) -> FuzzOutcome:
    """fuzz() against a service started on folder's PKI (ticket `ego`) at now_s, stopped afterwards."""
    service, ctx, radio = start_service(folder / "fuzz.pcap", now_s, signing_with(folder / "pki"))
    try:
        return fuzz(service, ctx, groups, packets, mutation=mutation)
    finally:
        service.stop()
        radio.close()


def run(packets: int, folder: Path) -> FuzzOutcome:
    now_s = time.time()
    groups = [real_seeds(), signed_seeds(folder / "pki", now_s), unsigned_seeds()]
    return run_in_service(folder, now_s, groups, packets)


def assert_every_packet_counted(outcome: FuzzOutcome, packets: int) -> None:
    """All packets passed, none stalled, each accepted, ignored as ours, taken as a beacon or rejected by reason."""
    assert outcome.packets == packets
    assert outcome.accepted + outcome.own + outcome.beacons + sum(outcome.rejected.values()) == packets
    assert outcome.slowest_packet_cpu_s < SLOWEST_PACKET_CPU_S


def print_outcome(outcome: FuzzOutcome, accepted_detail: str = "") -> None:
    """The run's figures, then the rejections by reason, most frequent first."""
    print(f"{outcome.packets} packets in {outcome.elapsed_s:.1f} s, {outcome.cpu_s:.1f} s of CPU "
          f"({outcome.packets / outcome.cpu_s:.0f}/s of CPU), slowest {outcome.slowest_packet_cpu_s * 1000:.1f} ms; "
          f"accepted {outcome.accepted}{accepted_detail}, own {outcome.own}, beacons {outcome.beacons}, "
          f"rejected {sum(outcome.rejected.values())} under {len(outcome.rejected)} reasons; "
          f"up to {outcome.stations_listed_max} stations listed")
    for reason, count in outcome.rejected.most_common():
        print(f"  {reason}: {count}")


def main(run_fuzz: Callable[[int, Path], FuzzOutcome] = run, description: str = __doc__) -> None:
    parser = argparse.ArgumentParser(description=description.splitlines()[0])
    parser.add_argument("--packets", type=int, default=100_000)
    args = parser.parse_args()
    with tempfile.TemporaryDirectory() as folder:
        outcome = run_fuzz(args.packets, Path(folder))
    print_outcome(outcome)
    print("security layer: " + ", ".join(f"{name.removeprefix('security_')} {count}"
                                          for name, count in sorted(outcome.security.items())))


if __name__ == "__main__":
    main()
