"""Messages of vulnerable road users (pedestrians, cyclists) that a station hears: the VAM of ETSI TS 103 300-3,
UPER to asn1tools dicts through the Release 2 modules (release2.py).

    value = VruCodec().decode(VruMessage.VAM, header, uper)   # or V2xDecodeError
"""

from __future__ import annotations

import enum

from coopdrive.v2x.btp import BtpPort
from coopdrive.v2x.port_message import PortMessage
from coopdrive.v2x.infrastructure import decode_port_message
from coopdrive.v2x.its_pdu import ItsHeader
from coopdrive.v2x.release2 import release2_spec

# TS 103 300-3 v2.1.1 sends VAMs with ItsPduHeader protocolVersion 3 (the CDD of TS 102 894-2 v2.x), as FlexStack
# does; v2.2.1 keeps it.
SUPPORTED_PROTOCOL_VERSIONS = (3,)


class VruMessage(PortMessage, enum.Enum):
    """Each message: (ItsPduHeader messageId of TS 102 894-2 v2, BTP port, top ASN.1 type)."""

    VAM = (16, BtpPort.VAM, "VAM")


VRU_OF_PORT = {int(message.port): message for message in VruMessage}


class VruCodec:
    def decode(self, message: VruMessage, header: ItsHeader, uper: bytes) -> dict:
        """The asn1tools value of a PDU whose header was peeked; raises V2xDecodeError with the reason."""
        return decode_port_message(release2_spec(), message, SUPPORTED_PROTOCOL_VERSIONS, header, uper)
