"""TS 103 097 v1.3.1 explicit certificates: issue (test PKI), parse, and the checks on one certificate.

Times are TAI seconds since 2004-01-01 (Time32), positions 0.1 microdegree (as in GeoNetworking).
"""

from __future__ import annotations

import math
from dataclasses import dataclass

from cryptography.hazmat.primitives.asymmetric import ec

from coopdrive.reasons import ReasonedError
from coopdrive.v2x.reasons import RejectReason
from coopdrive.v2x.security import asn
from coopdrive.v2x.security.canonical import canonical_certificate
from coopdrive.v2x.security.crypto import (
    data_digest, hashed_id8, public_key_choice, public_key_from_choice, sign_digest, verify_digest)
from coopdrive.v2x.units import EARTH_RADIUS_M, TENTH_MICRODEG_PER_DEG

CERTIFICATE_VERSION = 3
NO_CRACA_ID = bytes(3)
NO_CRL_SERIES = 0
# IEEE 1609.2 6.4.15: a "year" of Duration is 31 556 952 s.
DURATION_UNIT_S = {"microseconds": 1e-6, "milliseconds": 1e-3, "seconds": 1, "minutes": 60, "hours": 3600,
                   "sixtyHours": 216_000, "years": 31_556_952}
# eeType bits: app (authorisation tickets) and enrol (enrolment credentials).
EE_TYPE_APP_AND_ENROL = (b"\xc0", 8)
# A root issues authorities which issue tickets: chains root -> AA -> AT.
ROOT_MIN_CHAIN_LENGTH = 2
AUTHORITY_MIN_CHAIN_LENGTH = 1


class CertificateError(ReasonedError[RejectReason], ValueError):
    """A certificate that cannot be used; `reason` is the RejectReason to count."""


@dataclass(frozen=True)
class CircularArea:
    """A certificate region: centre and radius (what the test PKI issues)."""

    latitude_deg: float
    longitude_deg: float
    radius_m: float

    def to_asn(self) -> tuple[str, dict]:
        return "circularRegion", {"center": {"latitude": round(self.latitude_deg * TENTH_MICRODEG_PER_DEG),
                                             "longitude": round(self.longitude_deg * TENTH_MICRODEG_PER_DEG)},
                                  "radius": round(self.radius_m)}


@dataclass(frozen=True, eq=False)
class Certificate:
    """`encoded`: as received (or issued); `canonical`: the form it is hashed in (canonical.py), the same bytes
    unless a key or the signature's r came in another form; `digest`: its HashedId8, over `canonical`."""
    encoded: bytes
    value: dict
    digest: bytes
    public_key: ec.EllipticCurvePublicKey
    canonical: bytes

    @classmethod
    def from_value(cls, value: dict) -> Certificate:
        """From a decoded EtsiTs103097Certificate; raises CertificateError(INVALID_CERTIFICATE)."""
        try:
            encoded = asn.encode(asn.CERTIFICATE_TYPE, value)
            if value["version"] != CERTIFICATE_VERSION or value["type"] != "explicit" or "signature" not in value:
                raise ValueError("not a version 3 explicit certificate")
            key_choice, key = value["toBeSigned"]["verifyKeyIndicator"]
            if key_choice != "verificationKey":
                raise ValueError("no verification key")
            public_key = public_key_from_choice(key)
            canonical_value = canonical_certificate(value)
            canonical = encoded if canonical_value == value else asn.encode(asn.CERTIFICATE_TYPE, canonical_value)
        except CertificateError:
            raise
        except Exception as error:  # noqa: BLE001 -- asn1tools and OpenSSL raise many types on garbage
            raise CertificateError(RejectReason.INVALID_CERTIFICATE, f"{type(error).__name__}: {error}") from None
        return cls(encoded, value, hashed_id8(canonical), public_key, canonical)

    @classmethod
    def from_bytes(cls, data: bytes) -> Certificate:
        try:
            value = asn.decode(asn.CERTIFICATE_TYPE, data)
        except Exception as error:  # noqa: BLE001
            raise CertificateError(RejectReason.INVALID_CERTIFICATE, f"{type(error).__name__}: {error}") from None
        certificate = cls.from_value(value)
        if certificate.encoded != bytes(data):
            raise CertificateError(RejectReason.INVALID_CERTIFICATE, "not canonical OER")
        return certificate

    @property
    def tbs(self) -> dict:
        return self.value["toBeSigned"]

    @property
    def name(self) -> str:
        choice, value = self.tbs["id"]
        return value if choice == "name" else self.digest.hex()

    @property
    def is_self_signed(self) -> bool:
        return self.value["issuer"][0] == "self"

    @property
    def issuer_digest(self) -> bytes | None:
        choice, value = self.value["issuer"]
        return value if choice == "sha256AndDigest" else None

    @property
    def valid_from_s(self) -> int:
        return self.tbs["validityPeriod"]["start"]

    @property
    def valid_until_s(self) -> float:
        unit, count = self.tbs["validityPeriod"]["duration"]
        return self.valid_from_s + count * DURATION_UNIT_S[unit]

    @property
    def app_psids(self) -> frozenset[int]:
        return frozenset(entry["psid"] for entry in self.tbs.get("appPermissions", ()))

    @property
    def may_issue(self) -> bool:
        return bool(self.tbs.get("certIssuePermissions"))

    def check_validity(self, time_s: float) -> None:
        if time_s < self.valid_from_s:
            raise CertificateError(RejectReason.CERTIFICATE_NOT_YET_VALID, self.name)
        if time_s >= self.valid_until_s:
            raise CertificateError(RejectReason.CERTIFICATE_EXPIRED, self.name)

    def check_region(self, latitude: int, longitude: int) -> None:
        """Position in 0.1 microdegree; identified regions (country codes) are not checked here."""
        region = self.tbs.get("region")
        if region is not None and not region_contains(region, latitude, longitude):
            raise CertificateError(RejectReason.OUTSIDE_CERTIFICATE_REGION, self.name)

    def signature_is_from(self, issuer: Certificate | None) -> bool:
        """The certificate signature checks against the issuer's key (None: self-signed)."""
        tbs = asn.encode(asn.TBS_CERTIFICATE_TYPE, self.tbs)
        key = issuer.public_key if issuer is not None else self.public_key
        digest = data_digest(tbs, issuer.canonical if issuer is not None else None)
        return verify_digest(key, self.value["signature"], digest)


def issue_certificate(name: str, subject_key: ec.EllipticCurvePublicKey, signing_key: ec.EllipticCurvePrivateKey,
                      issuer: Certificate | None = None, *, start_s: int, duration_hours: int, app_psids: tuple[int, ...] = (),
                      min_chain_length: int | None = None, region: CircularArea | None = None,
                      uncompressed_key: bool = False) -> Certificate:
    """Issue a certificate signed with signing_key: the issuer's key, or the subject's own for a root (issuer None).

    Tickets get appPermissions (psid with an empty bitmap SSP), authorities certIssuePermissions.
    """
    tbs: dict = {"id": ("name", name), "cracaId": NO_CRACA_ID, "crlSeries": NO_CRL_SERIES,
                 "validityPeriod": {"start": start_s, "duration": ("hours", duration_hours)},
                 "verifyKeyIndicator": ("verificationKey", public_key_choice(subject_key, uncompressed_key))}
    if region is not None:
        tbs["region"] = region.to_asn()
    if app_psids:
        tbs["appPermissions"] = [{"psid": psid, "ssp": ("bitmapSsp", b"\x01")} for psid in app_psids]
    if min_chain_length is not None:
        tbs["certIssuePermissions"] = [{"subjectPermissions": ("all", None), "minChainLength": min_chain_length,
                                        "chainLengthRange": 0, "eeType": EE_TYPE_APP_AND_ENROL}]
    tbs_bytes = asn.encode(asn.TBS_CERTIFICATE_TYPE, tbs)
    if issuer is None:
        issuer_id, digest = ("self", "sha256"), data_digest(tbs_bytes, None)
    else:
        issuer_id, digest = ("sha256AndDigest", issuer.digest), data_digest(tbs_bytes, issuer.canonical)
    value = {"version": CERTIFICATE_VERSION, "type": "explicit", "issuer": issuer_id, "toBeSigned": tbs,
             "signature": sign_digest(signing_key, digest)}
    return Certificate.from_value(value)


def region_contains(region: tuple[str, object], latitude: int, longitude: int) -> bool:
    kind, value = region
    if kind == "circularRegion":
        centre = value["center"]
        return _distance_m(centre["latitude"], centre["longitude"], latitude, longitude) <= value["radius"]
    if kind == "rectangularRegion":
        return any(r["southEast"]["latitude"] <= latitude <= r["northWest"]["latitude"]
                   and r["northWest"]["longitude"] <= longitude <= r["southEast"]["longitude"] for r in value)
    if kind == "polygonalRegion":
        return _in_polygon([(p["latitude"], p["longitude"]) for p in value], latitude, longitude)
    return True


def _distance_m(lat_a: int, lon_a: int, lat_b: int, lon_b: int) -> float:
    phi_a, phi_b = math.radians(lat_a / TENTH_MICRODEG_PER_DEG), math.radians(lat_b / TENTH_MICRODEG_PER_DEG)
    d_phi, d_lambda = phi_b - phi_a, math.radians((lon_b - lon_a) / TENTH_MICRODEG_PER_DEG)
    h = math.sin(d_phi / 2) ** 2 + math.cos(phi_a) * math.cos(phi_b) * math.sin(d_lambda / 2) ** 2
    return 2 * EARTH_RADIUS_M * math.asin(min(1.0, math.sqrt(h)))


def _in_polygon(vertices: list[tuple[int, int]], latitude: int, longitude: int) -> bool:
    inside = False
    for (lat_i, lon_i), (lat_j, lon_j) in zip(vertices, vertices[-1:] + vertices[:-1]):
        if (lat_i > latitude) != (lat_j > latitude):
            crossing = lon_i + (latitude - lat_i) * (lon_j - lon_i) / (lat_j - lat_i)
            if longitude < crossing:
                inside = not inside
    return inside
