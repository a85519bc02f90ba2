"""Infrastructure messages of ETSI TS 103 301: SPATEM, MAPEM, SREM and SSEM, UPER to asn1tools dicts.

    value = InfrastructureCodec().decode(InfrastructureMessage.SPATEM, uper)   # or V2xDecodeError

One set of modules (asn1/dsrc: ETSI-ITS-DSRC of TS 103 301 v2.2.1 with its CDD) reads both protocol versions
roadside units send. Version 1 (TS 103 301 v1.x, the DSRC types of ISO TS 19091 2016) and version 2 encode the
ItsPduHeader the same way, and what v2.x added to the DSRC types sits behind extension markers, which a
version-1 message leaves empty; a version-2 sender's additions we do not know are skipped by asn1tools (an
unknown CHOICE alternative reads as (None, None), an unknown ENUMERATED value as None: the mappings take both).
IVIM (ISO TS 19321) is named by its port only: its module is not among ours.
"""

from __future__ import annotations

import enum

from coopdrive.v2x.asn1_package import PackageSpec
from coopdrive.v2x.btp import BtpPort
from coopdrive.v2x.port_message import PortMessage
from coopdrive.v2x.its_pdu import PROTOCOL_VERSION_CURRENT, PROTOCOL_VERSION_GCDC, ItsHeader
from coopdrive.v2x.reasons import RejectReason, V2xDecodeError
from coopdrive.v2x.recent_decodes import RECENT_DECODES

SUPPORTED_PROTOCOL_VERSIONS = (PROTOCOL_VERSION_GCDC, PROTOCOL_VERSION_CURRENT)
_SPEC = PackageSpec("coopdrive.v2x.asn1.dsrc", "dsrc")


class InfrastructureMessage(PortMessage, enum.Enum):
    """Each message: (ItsPduHeader messageId of TS 102 894-2, BTP port, top ASN.1 type)."""

    SPATEM = (4, BtpPort.SPATEM, "SPATEM")
    MAPEM = (5, BtpPort.MAPEM, "MAPEM")
    SREM = (9, BtpPort.SREM, "SREM")
    SSEM = (10, BtpPort.SSEM, "SSEM")


INFRASTRUCTURE_OF_PORT = {int(message.port): message for message in InfrastructureMessage}


def decode_port_message(spec, message, protocol_versions: tuple[int, ...], header: ItsHeader, uper: bytes) -> dict:
    """The asn1tools value of a message known by its BTP port (message: message_id, port, type_name, name), its
    header peeked; V2xDecodeError with the reason for a header that does not fit or bytes that do not decode."""
    if header.message_id != message.message_id:
        raise V2xDecodeError(RejectReason.MESSAGE_ID_PORT_MISMATCH,
                             f"messageID {header.message_id} on port {int(message.port)}")
    if header.protocol_version not in protocol_versions:
        raise V2xDecodeError(RejectReason.UNSUPPORTED_PROTOCOL_VERSION,
                             f"{message.name} protocolVersion {header.protocol_version}")
    # Shared with every codec of the process (RECENT_DECODES), keyed by the type too: messageId 10 is an SSEM on
    # port 2008 but an iCLCM on 2010. No ITS PDU's key starts so (its first octet, protocolVersion, is 1 to 3).
    key = message.type_name.encode() + bytes(uper)
    value = RECENT_DECODES.get(key)
    if value is not None:
        return value
    try:
        value = spec.decode(message.type_name, bytes(uper))
    except Exception as error:  # noqa: BLE001 -- asn1tools raises many types on garbage input
        raise V2xDecodeError(RejectReason.MALFORMED_ASN1, f"{type(error).__name__}: {error}") from None
    RECENT_DECODES.keep(key, value)
    return value


class InfrastructureCodec:
    """UPER decoding (and, for tests and tools, encoding) of the four messages."""

    @staticmethod
    def spec():
        return _SPEC.get()

    def decode(self, message: InfrastructureMessage, header: ItsHeader, uper: bytes) -> dict:
        """The asn1tools value of a PDU whose header was peeked; raises V2xDecodeError with the reason."""
        return decode_port_message(self.spec(), message, SUPPORTED_PROTOCOL_VERSIONS, header, uper)

    def encode(self, message: InfrastructureMessage, value: dict) -> bytes:
        return self.spec().encode(message.type_name, value, check_constraints=True)
