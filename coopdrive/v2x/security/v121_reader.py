"""The wire encoding of ETSI TS 103 097 v1.2.1 (the secured packets of the GCDC years): a TLS-style presentation
language, read here field by field, and its wire numbers.

Fixed-size integers are big-endian. A variable-length vector `<var>` is preceded by its length in octets, and an
IntX (an ITS-AID) is an unsigned integer, both in the same self-delimiting code (v1.2.1 clause 4.1 and 4.2.1): the
number of leading 1 bits of the first octet is the number of octets that follow; the bits after the first 0 bit,
with those octets, are the value (0x24 = 36; 0x80 0x8D = 141). Every read past the end of its vector raises
V2xDecodeError(malformed_security_envelope), never anything else.
"""

from __future__ import annotations

import enum

from coopdrive.v2x.reasons import RejectReason, V2xDecodeError

PROTOCOL_VERSION = 2
CERTIFICATE_VERSION = 2
# Field size of NIST P-256 coordinates and of the signature's s.
FIELD_SIZE = 32
HASHED_ID8_SIZE = 8
HASHED_ID3_SIZE = 3
NONCE_SIZE = 12
BITS_PER_OCTET = 8
# Value bits per octet of the length code: one bit of each octet is spent on the count of octets that follow.
_VALUE_BITS_PER_OCTET = 7
# More octets than this would give lengths no V2X packet can have; refused rather than read.
_MAX_EXTRA_LENGTH_OCTETS = 4


class PublicKeyAlgorithm(enum.IntEnum):
    ECDSA_NISTP256_WITH_SHA256 = 0
    ECIES_NISTP256 = 1


class EccPointType(enum.IntEnum):
    X_COORDINATE_ONLY = 0
    COMPRESSED_LSB_Y_0 = 2
    COMPRESSED_LSB_Y_1 = 3
    UNCOMPRESSED = 4


class SignerInfoType(enum.IntEnum):
    SELF = 0
    CERTIFICATE_DIGEST_WITH_SHA256 = 1
    CERTIFICATE = 2
    CERTIFICATE_CHAIN = 3
    CERTIFICATE_DIGEST_WITH_OTHER_ALGORITHM = 4


class HeaderFieldType(enum.IntEnum):
    GENERATION_TIME = 0
    GENERATION_TIME_STANDARD_DEVIATION = 1
    EXPIRATION = 2
    GENERATION_LOCATION = 3
    REQUEST_UNRECOGNIZED_CERTIFICATE = 4
    ITS_AID = 5
    SIGNER_INFO = 128
    ENCRYPTION_PARAMETERS = 129
    RECIPIENT_INFO = 130


class PayloadType(enum.IntEnum):
    UNSECURED = 0
    SIGNED = 1
    ENCRYPTED = 2
    SIGNED_EXTERNAL = 3
    SIGNED_AND_ENCRYPTED = 4


class TrailerFieldType(enum.IntEnum):
    SIGNATURE = 1


class SubjectAttributeType(enum.IntEnum):
    VERIFICATION_KEY = 0
    ENCRYPTION_KEY = 1
    ASSURANCE_LEVEL = 2
    RECONSTRUCTION_VALUE = 3
    ITS_AID_LIST = 32
    ITS_AID_SSP_LIST = 33


class ValidityRestrictionType(enum.IntEnum):
    TIME_END = 0
    TIME_START_AND_END = 1
    TIME_START_AND_DURATION = 2
    REGION = 3


class RegionType(enum.IntEnum):
    NONE = 0
    CIRCLE = 1
    RECTANGLE = 2
    POLYGON = 3
    ID = 4


class SymmetricAlgorithm(enum.IntEnum):
    AES_128_CCM = 0


def malformed(detail: str) -> V2xDecodeError:
    return V2xDecodeError(RejectReason.MALFORMED_SECURITY_ENVELOPE, f"TS 103 097 v1.2.1: {detail}")


def encode_length(value: int) -> bytes:
    """The length (or IntX) code of value, in the fewest octets."""
    extra = 0
    while value >= 1 << (_VALUE_BITS_PER_OCTET * (extra + 1)):
        extra += 1
    octets = extra + 1
    prefix = ((1 << extra) - 1) << (BITS_PER_OCTET * octets - extra)
    return (prefix | value).to_bytes(octets, "big")


class PresentationReader:
    """A cursor over data[offset:end]; var_reader() hands out the vector that follows as a reader of its own."""

    def __init__(self, data: bytes, offset: int = 0, end: int | None = None):
        self.data, self.offset = data, offset
        self.end = len(data) if end is None else end

    @property
    def at_end(self) -> bool:
        return self.offset >= self.end

    def fixed(self, size: int) -> bytes:
        if self.offset + size > self.end:
            raise malformed(f"{size} octets wanted at {self.offset}, {self.end - self.offset} left")
        value = self.data[self.offset:self.offset + size]
        self.offset += size
        return value

    def uint(self, size: int) -> int:
        return int.from_bytes(self.fixed(size), "big")

    def sint(self, size: int) -> int:
        return int.from_bytes(self.fixed(size), "big", signed=True)

    def u8(self) -> int:
        return self.uint(1)

    def length(self) -> int:
        """A length or IntX in the self-delimiting code."""
        first = self.u8()
        extra = 0
        while extra < BITS_PER_OCTET and first & (0x80 >> extra):
            extra += 1
        if extra > _MAX_EXTRA_LENGTH_OCTETS:
            raise malformed(f"length code 0x{first:02x} of {extra} more octets")
        value = first & ((1 << (BITS_PER_OCTET - extra - 1)) - 1)
        for octet in self.fixed(extra):
            value = (value << BITS_PER_OCTET) | octet
        return value

    def var_reader(self) -> PresentationReader:
        size = self.length()
        start = self.offset
        self.fixed(size)
        return PresentationReader(self.data, start, start + size)

    def var_opaque(self) -> bytes:
        vector = self.var_reader()
        return vector.data[vector.offset:vector.end]
