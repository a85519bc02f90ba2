"""Trusted roots, known authorities and a bounded cache of authorisation tickets heard on the air.

A ticket is usable when the chain ticket -> authority -> root checks: every certificate valid at the
message's generation time and (where it has a region) around the sender, every signature by the
issuer's key, the last link a self-signed root we were told to trust. Authorities are known, not trusted:
a chain that ends in a root outside the trusted set is refused as UNTRUSTED_ROOT.
"""

from __future__ import annotations

from collections import OrderedDict
from collections.abc import Iterable

from coopdrive.v2x.reasons import RejectReason
from coopdrive.v2x.security.certificate import Certificate, CertificateError
from coopdrive.v2x.security.crypto import hashed_id8

DEFAULT_TICKET_CACHE_SIZE = 4096
# root -> authority -> ticket; anything deeper is refused rather than walked.
MAX_CHAIN_LENGTH = 3


class CertificateStore:
    def __init__(self, trusted_roots: Iterable[Certificate] = (), authorities: Iterable[Certificate] = (),
                 ticket_cache_size: int = DEFAULT_TICKET_CACHE_SIZE):
        self._trusted: dict[bytes, Certificate] = {}
        self._issuers: dict[bytes, Certificate] = {}
        self._tickets: OrderedDict[bytes, Certificate] = OrderedDict()
        self._signature_checked: set[bytes] = set()
        self._ticket_cache_size = ticket_cache_size
        for root in trusted_roots:
            self.trust_root(root)
        for authority in authorities:
            self.add_authority(authority)

    def trust_root(self, root: Certificate) -> None:
        if not root.is_self_signed or not root.signature_is_from(None):
            raise CertificateError(RejectReason.INVALID_CERTIFICATE_SIGNATURE, f"root {root.name}")
        self._trusted[root.digest] = root
        self._issuers[root.digest] = root
        self._signature_checked.add(root.digest)

    def add_authority(self, certificate: Certificate) -> None:
        """Make an issuing certificate (authority, or an untrusted root) known for chain building."""
        if not certificate.may_issue:
            raise CertificateError(RejectReason.INVALID_CERTIFICATE, f"{certificate.name} may not issue")
        self._issuers[certificate.digest] = certificate

    @property
    def has_trusted_roots(self) -> bool:
        return bool(self._trusted)

    def is_trusted(self, digest: bytes) -> bool:
        return digest in self._trusted

    def resolve(self, digest: bytes) -> Certificate | None:
        """A ticket heard before (as a full certificate that passed check_chain), by its HashedId8."""
        ticket = self._tickets.get(digest)
        if ticket is not None:
            self._tickets.move_to_end(digest)
        return ticket

    def sent_in_full(self, encoded: bytes, value: dict) -> Certificate:
        """The certificate a packet carries in full (`encoded` as sent, `value` decoded): the one remembered when
        the same bytes came before, else parsed (CertificateError). A certificate in canonical form is found by the
        digest of its bytes; one sent in another form is parsed each time."""
        known = self.resolve(hashed_id8(encoded))
        if known is not None and known.encoded == encoded:
            return known
        return Certificate.from_value(value)

    def remember(self, ticket: Certificate) -> None:
        self._tickets[ticket.digest] = ticket
        self._tickets.move_to_end(ticket.digest)
        while len(self._tickets) > self._ticket_cache_size:
            forgotten, _ = self._tickets.popitem(last=False)
            self._signature_checked.discard(forgotten)

    def check_chain(self, ticket: Certificate, time_s: float, latitude: int | None, longitude: int | None) -> None:
        """Raise CertificateError naming the first thing wrong in ticket -> ... -> trusted root.

        latitude / longitude None (sender position unknown): regions are not checked."""
        if ticket.may_issue or not ticket.app_psids:
            raise CertificateError(RejectReason.INVALID_CERTIFICATE, f"{ticket.name} is no authorisation ticket")
        current = ticket
        for _ in range(MAX_CHAIN_LENGTH):
            current.check_validity(time_s)
            if latitude is not None and longitude is not None:
                current.check_region(latitude, longitude)
            if current.is_self_signed:
                if current.digest not in self._trusted:
                    raise CertificateError(RejectReason.UNTRUSTED_ROOT, current.name)
                return
            issuer_digest = current.issuer_digest
            if issuer_digest is None:
                raise CertificateError(RejectReason.UNKNOWN_ISSUER, f"{current.name}: issuer not a SHA-256 digest")
            issuer = self._issuers.get(issuer_digest)
            if issuer is None:
                raise CertificateError(RejectReason.UNKNOWN_ISSUER, f"{current.name} issued by {issuer_digest.hex()}")
            if current.digest not in self._signature_checked:
                if not current.signature_is_from(issuer):
                    raise CertificateError(RejectReason.INVALID_CERTIFICATE_SIGNATURE, current.name)
                self._signature_checked.add(current.digest)
            current = issuer
        raise CertificateError(RejectReason.UNKNOWN_ISSUER, f"chain of {ticket.name} longer than {MAX_CHAIN_LENGTH}")
