"""ITS PDUs (CAM, DENM, iCLCM) in ASN.1 UPER, schema chosen by ItsPduHeader.protocolVersion: the layer under
packet.py, which is the V2X codec's one facade (GeoNetworking + BTP + UPER).

Parsing the modules takes about a second per set, so the parsed specification is cached on disk
($XDG_CACHE_HOME/coopdrive/asn1 or ~/.cache/coopdrive/asn1) and later start-ups take tens of ms.
asn1tools' own cache_dir needs the optional diskcache package, which the stack does not depend on, so
it is used when present and otherwise the parsed dict is cached by coopdrive/v2x/asn1_cache.py.
"""

from __future__ import annotations

import enum
import os
import struct
from importlib import resources
from pathlib import Path
from typing import NamedTuple

import asn1tools

from coopdrive.v2x.asn1_cache import parsed_cached
from coopdrive.v2x.reasons import RejectReason, V2xDecodeError, V2xEncodeError
from coopdrive.v2x.recent_decodes import RECENT_DECODES

# ItsPduHeader: protocolVersion (8 bits), messageID (8 bits), stationID (32 bits); the PDUs start with it
# and have no preamble, so these are the first six octets of every UPER message.
ITS_HEADER_SIZE_BYTES = 6
_ITS_HEADER = struct.Struct(">BBI")

PROTOCOL_VERSION_GCDC = 1
PROTOCOL_VERSION_CURRENT = 2

_V1_FILES = ("ITS_CAM_v1.3.2.asn", "ITS_DENM_v1.2.2.asn", "iCLCM-reconstructed.asn")
_V2_FILES = ("v2/TS102894-2v131-CDD.asn", "v2/EN302637-2v141-CAM.asn", "v2/EN302637-3v131-DENM.asn")


class ItsMessageId(enum.IntEnum):
    """ItsPduHeader.messageID of the messages this codec knows."""

    DENM = 1
    CAM = 2
    ICLCM = 10


_MESSAGE_ID_BY_NUMBER = {int(member): member for member in ItsMessageId}
PDU_TYPE_NAMES = {
    ItsMessageId.CAM: "CAM",
    ItsMessageId.DENM: "DENM",
    ItsMessageId.ICLCM: "IgameCooperativeLaneChangeMessage",
}


class ItsHeader(NamedTuple):
    protocol_version: int
    message_id: int
    station_id: int


def peek_its_header(uper: bytes) -> ItsHeader:
    """Read the ItsPduHeader without decoding the rest (to pick the schema)."""
    if len(uper) < ITS_HEADER_SIZE_BYTES:
        raise V2xDecodeError(RejectReason.TRUNCATED_ITS_HEADER, f"{len(uper)} bytes")
    return ItsHeader(*_ITS_HEADER.unpack_from(uper))


def default_cache_dir() -> Path:
    base = os.environ.get("XDG_CACHE_HOME") or os.path.join(os.path.expanduser("~"), ".cache")
    return Path(base) / "coopdrive" / "asn1"


def _asn_path(name: str) -> str:
    return str(resources.files("coopdrive.v2x.asn1").joinpath(name))


class ItsCodec:
    """UPER encode/decode of ITS PDUs (asn1tools dicts) for protocol versions 1 (GCDC) and 2."""

    def __init__(self, cache_dir: Path | None = None):
        self._cache_dir = Path(cache_dir) if cache_dir is not None else default_cache_dir()
        self._specs: dict[int, asn1tools.compiler.Specification] = {}
        # (protocolVersion, messageID) -> (specification, PDU type name), filled as packets arrive
        self._schemas: dict[tuple[int, int], tuple[asn1tools.compiler.Specification, str]] = {}

    def spec(self, protocol_version: int) -> asn1tools.compiler.Specification:
        if protocol_version not in self._specs:
            if protocol_version == PROTOCOL_VERSION_GCDC:
                files = _V1_FILES
            elif protocol_version == PROTOCOL_VERSION_CURRENT:
                files = _V2_FILES
            else:
                raise V2xDecodeError(RejectReason.UNSUPPORTED_PROTOCOL_VERSION, str(protocol_version))
            self._specs[protocol_version] = self._compile([_asn_path(f) for f in files])
        return self._specs[protocol_version]

    def _compile(self, paths: list[str]) -> asn1tools.compiler.Specification:
        if getattr(asn1tools.compiler, "has_diskcache", False):
            return asn1tools.compile_files(paths, "uper", cache_dir=str(self._cache_dir))
        parsed = parsed_cached(paths, self._cache_dir, "parsed")
        return asn1tools.compile_dict(parsed, "uper")

    def encode(self, message_id: ItsMessageId, value: dict, check_ranges: bool = True) -> bytes:
        """Encode a PDU dict; its header's protocolVersion picks the schema. Raises V2xEncodeError.

        check_ranges=False skips asn1tools' type and constraint checks, which take a third of the time of a
        CAM's encoding. Only for dicts that the mappings built: they clamp every field into its range (a
        property test feeds them arbitrary content), so the checks could not fail there; anything else,
        such as a hand-written dict, must be checked since UPER would silently truncate a value out of range.
        """
        version = value["header"]["protocolVersion"]
        try:
            self._check_supported(message_id, version)
            return self.spec(version).encode(PDU_TYPE_NAMES[message_id], value, check_types=check_ranges,
                                             check_constraints=check_ranges)
        except (V2xDecodeError, asn1tools.Error) as error:
            raise V2xEncodeError(f"{message_id.name}: {error}") from None

    def decode(self, uper: bytes) -> tuple[ItsHeader, dict]:
        """Decode any known PDU; raises V2xDecodeError, never anything else."""
        header = peek_its_header(uper)
        return header, self.decode_with_header(header, uper)

    def decode_with_header(self, header: ItsHeader, uper: bytes) -> dict:
        """decode() for a caller that has peeked the header already. The value may be shared with other callers
        (recent_decodes.py): read it, do not change it."""
        schema = self._schemas.get((header.protocol_version, header.message_id))
        if schema is None:
            schema = self._schema_of(header)
        uper = bytes(uper)  # the key must not change under the memo (bytes(b) is b itself)
        value = RECENT_DECODES.get(uper)
        if value is not None:
            return value
        spec, type_name = schema
        try:
            value = spec.decode(type_name, uper)
        except Exception as error:  # noqa: BLE001 -- asn1tools raises many types on garbage input
            raise V2xDecodeError(RejectReason.MALFORMED_ASN1, f"{type(error).__name__}: {error}") from None
        RECENT_DECODES.keep(uper, value)
        return value

    def _schema_of(self, header: ItsHeader) -> tuple[asn1tools.compiler.Specification, str]:
        """The compiled schema and type name for a header, remembered; raises the reason it has none."""
        message_id = _MESSAGE_ID_BY_NUMBER.get(header.message_id)
        if message_id is None:
            raise V2xDecodeError(RejectReason.MESSAGE_ID_PORT_MISMATCH, f"messageID {header.message_id}")
        self._check_supported(message_id, header.protocol_version)
        schema = (self.spec(header.protocol_version), PDU_TYPE_NAMES[message_id])
        self._schemas[header.protocol_version, header.message_id] = schema
        return schema

    @staticmethod
    def _check_supported(message_id: ItsMessageId, protocol_version: int) -> None:
        supported = (PROTOCOL_VERSION_GCDC,) if message_id == ItsMessageId.ICLCM else (
            PROTOCOL_VERSION_GCDC, PROTOCOL_VERSION_CURRENT)
        if protocol_version not in supported:
            raise V2xDecodeError(
                RejectReason.UNSUPPORTED_PROTOCOL_VERSION, f"{message_id.name} protocolVersion {protocol_version}")
