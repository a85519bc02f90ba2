"""A test PKI on disk (root CA -> authorisation authority -> per-vehicle authorisation tickets) and faults.

    DIR/root.cert  root.key.pem  aa.cert  aa.key.pem
    DIR/vehicles/NAME/ticket-K.cert  ticket-K.key.pem        (K = 0 .. tickets_per_vehicle - 1)

Certificates are TS 103 097 v1.3.1 explicit certificates in canonical OER, keys PKCS#8 PEM without a
password: for test tracks and simulation only, never for a vehicle on a public road.
"""

from __future__ import annotations

import sys
import time
from collections.abc import Sequence
from dataclasses import dataclass, field
from pathlib import Path

from cryptography.hazmat.primitives.asymmetric import ec

from coopdrive.exit_status import EXIT_FAILED, EXIT_OK
from coopdrive.v2x.geonet import BASIC_HEADER_SIZE
from coopdrive.v2x.security.certificate import (
    AUTHORITY_MIN_CHAIN_LENGTH, ROOT_MIN_CHAIN_LENGTH, Certificate, CircularArea, issue_certificate)
from coopdrive.v2x.security.crypto import (
    Curve, curve_of_key, generate_key, load_private_key_pem, private_key_pem)
from coopdrive.v2x.security.envelope import parse_signed_data
from coopdrive.v2x.security.profile import ROADSIDE_TICKET_PSIDS, TICKET_PSIDS
from coopdrive.v2x.security.signer import SecuredPacketSigner
from coopdrive.v2x.security.store import CertificateStore
from coopdrive.v2x.timebase import MS_PER_S, tai_ms_from_unix_s

ROOT_VALIDITY_HOURS = 5 * 365 * 24
AUTHORITY_VALIDITY_HOURS = 2 * 365 * 24
TICKET_VALIDITY_HOURS = 7 * 24
# Validity starts a little in the past so that a clock slightly behind ours still accepts the tickets.
BACKDATE_S = 3600
EXPIRED_TICKET_AGE_S = 2 * 24 * 3600
DEFAULT_TICKETS_PER_VEHICLE = 3
ROOT_NAME, AUTHORITY_NAME = "root", "aa"
BITS_PER_BYTE = 8

Ticket = tuple[Certificate, ec.EllipticCurvePrivateKey]


@dataclass
class TestPki:
    directory: Path
    root: Certificate
    root_key: ec.EllipticCurvePrivateKey
    authority: Certificate
    authority_key: ec.EllipticCurvePrivateKey
    tickets: dict[str, list[Ticket]] = field(default_factory=dict)

    def store(self) -> CertificateStore:
        """A store trusting this root and knowing this authority (what every vehicle of the test loads)."""
        return CertificateStore(trusted_roots=[self.root], authorities=[self.authority])

    def signer(self, vehicle: str, station_id: int | None = None, mac: bytes | None = None) -> SecuredPacketSigner:
        return SecuredPacketSigner(self.tickets[vehicle], station_id, mac)

    def issue_ticket(self, name: str, *, start_s: int | None = None, duration_hours: int = TICKET_VALIDITY_HOURS,
                     region: CircularArea | None = None, psids: tuple[int, ...] = TICKET_PSIDS,
                     uncompressed_key: bool = False) -> Ticket:
        """uncompressed_key: the ticket carries its key uncompressed, as another open stack's tickets do."""
        key = generate_key(curve_of_key(self.authority_key))
        ticket = issue_certificate(name, key.public_key(), self.authority_key, self.authority,
                                   start_s=_now_tai_s() - BACKDATE_S if start_s is None else start_s,
                                   duration_hours=duration_hours, app_psids=psids, region=region,
                                   uncompressed_key=uncompressed_key)
        return ticket, key


def create_test_pki(directory: str | Path, vehicles: Sequence[str] = (), curve: Curve = Curve.NIST_P256,
                    tickets_per_vehicle: int = DEFAULT_TICKETS_PER_VEHICLE,
                    region: CircularArea | None = None, valid_from_tai_s: int | None = None,
                    roadside_units: Sequence[str] = ()) -> TestPki:
    """Create and write a root, an authority and tickets_per_vehicle tickets per vehicle (region: tickets'); those
    of vehicles named in roadside_units permit SPATEM and MAPEM as well.

    Everything is valid from valid_from_tai_s (TAI seconds since 2004; default an hour ago): a simulated run
    whose clock starts in 2016 needs certificates valid then.
    """
    directory = Path(directory)
    start_s = _now_tai_s() - BACKDATE_S if valid_from_tai_s is None else valid_from_tai_s
    root_key = generate_key(curve)
    root = issue_certificate(ROOT_NAME, root_key.public_key(), root_key, None, start_s=start_s,
                             duration_hours=ROOT_VALIDITY_HOURS, min_chain_length=ROOT_MIN_CHAIN_LENGTH)
    authority_key = generate_key(curve)
    authority = issue_certificate(AUTHORITY_NAME, authority_key.public_key(), root_key, root, start_s=start_s,
                                  duration_hours=AUTHORITY_VALIDITY_HOURS,
                                  min_chain_length=AUTHORITY_MIN_CHAIN_LENGTH)
    pki = TestPki(directory, root, root_key, authority, authority_key)
    directory.mkdir(parents=True, exist_ok=True)
    _write(directory, ROOT_NAME, root, root_key)
    _write(directory, AUTHORITY_NAME, authority, authority_key)
    for vehicle in vehicles:
        folder = directory / "vehicles" / vehicle
        folder.mkdir(parents=True, exist_ok=True)
        pki.tickets[vehicle] = []
        for index in range(tickets_per_vehicle):
            ticket = pki.issue_ticket(f"{vehicle}-{index}", start_s=start_s, region=region, psids=ROADSIDE_TICKET_PSIDS
                                      if vehicle in roadside_units else TICKET_PSIDS)
            _write(folder, f"ticket-{index}", *ticket)
            pki.tickets[vehicle].append(ticket)
    return pki


def load_test_pki(directory: str | Path) -> TestPki:
    directory = Path(directory)
    root, root_key = _read(directory, ROOT_NAME)
    authority, authority_key = _read(directory, AUTHORITY_NAME)
    pki = TestPki(directory, root, root_key, authority, authority_key)
    for folder in sorted((directory / "vehicles").glob("*")):
        names = sorted(path.name.removesuffix(".cert") for path in folder.glob("ticket-*.cert"))
        pki.tickets[folder.name] = [_read(folder, name) for name in names]
    return pki


def pki_init(directory: str | Path, vehicles: Sequence[str], curve: Curve = Curve.NIST_P256) -> int:
    """`coopdrive pki init DIR`: write a test PKI; refuses to overwrite one. Returns the exit status."""
    directory = Path(directory)
    if (directory / f"{ROOT_NAME}.cert").exists():
        print(f"{directory} already holds a PKI (root.cert); not overwriting", file=sys.stderr)
        return EXIT_FAILED
    pki = create_test_pki(directory, vehicles, curve)
    print(f"root {pki.root.digest.hex()}  authority {pki.authority.digest.hex()}  ({curve.value})")
    for vehicle, tickets in pki.tickets.items():
        print(f"{vehicle}: " + " ".join(ticket.digest.hex() for ticket, _ in tickets))
    return EXIT_OK


def create_untrusted_pki(directory: str | Path, vehicles: Sequence[str] = ("rogue",),
                         curve: Curve = Curve.NIST_P256, valid_from_tai_s: int | None = None) -> TestPki:
    """Fault: a complete PKI under a root nobody trusts (tickets that chain to it must be refused)."""
    return create_test_pki(directory, vehicles, curve, valid_from_tai_s=valid_from_tai_s)


def issue_expired_ticket(pki: TestPki, vehicle: str) -> Ticket:
    """Fault: a ticket from the real authority whose validity ended a day ago (written as expired-ticket)."""
    ticket = pki.issue_ticket(f"{vehicle}-expired", start_s=_now_tai_s() - EXPIRED_TICKET_AGE_S, duration_hours=1)
    folder = pki.directory / "vehicles" / vehicle
    folder.mkdir(parents=True, exist_ok=True)
    _write(folder, "expired-ticket", *ticket)
    return ticket


def issue_expiring_tickets(pki: TestPki, vehicle: str, expiry_tai_s: int, not_before_tai_s: int) -> list[Ticket]:
    """Fault: replace the vehicle's tickets (same count, same files) by ones valid from at most not_before_tai_s
    until exactly expiry_tai_s (TAI seconds), e.g. a simulated run's ticket_expired fault."""
    hours = max(1, -(-(expiry_tai_s - not_before_tai_s) // 3600))
    folder = pki.directory / "vehicles" / vehicle
    tickets = []
    for index in range(len(pki.tickets[vehicle])):
        ticket = pki.issue_ticket(f"{vehicle}-{index}", start_s=expiry_tai_s - hours * 3600, duration_hours=hours)
        _write(folder, f"ticket-{index}", *ticket)
        tickets.append(ticket)
    pki.tickets[vehicle] = tickets
    return tickets


def tamper_packet(secured_packet: bytes, bit_in_message: int = 0) -> bytes:
    """Fault: the secured packet with one bit of its signed GN payload flipped, counted from the payload's end
    (bit 0: the last bit of the facility message), as a man in the middle changing a value would."""
    envelope = parse_signed_data(secured_packet[BASIC_HEADER_SIZE:])
    start = secured_packet.index(envelope.unsecured, BASIC_HEADER_SIZE)
    position = start + len(envelope.unsecured) - 1 - bit_in_message // BITS_PER_BYTE
    tampered = bytearray(secured_packet)
    tampered[position] ^= 1 << (bit_in_message % BITS_PER_BYTE)
    return bytes(tampered)


def _now_tai_s() -> int:
    return tai_ms_from_unix_s(time.time()) // MS_PER_S


def _write(folder: Path, name: str, certificate: Certificate, key: ec.EllipticCurvePrivateKey) -> None:
    (folder / f"{name}.cert").write_bytes(certificate.encoded)
    key_path = folder / f"{name}.key.pem"
    key_path.write_bytes(private_key_pem(key))
    key_path.chmod(0o600)


def _read(folder: Path, name: str) -> tuple[Certificate, ec.EllipticCurvePrivateKey]:
    return (Certificate.from_bytes((folder / f"{name}.cert").read_bytes()),
            load_private_key_pem((folder / f"{name}.key.pem").read_bytes()))
