"""What a message known by its BTP port is named by: (ItsPduHeader messageId, BTP port, top ASN.1 type)."""

from __future__ import annotations

from coopdrive.v2x.btp import BtpPort


class PortMessage:
    """Mixed into an enum whose values are (messageId, BTP port, top ASN.1 type name)."""

    value: tuple[int, BtpPort, str]

    @property
    def message_id(self) -> int:
        return self.value[0]

    @property
    def port(self) -> BtpPort:
        return self.value[1]

    @property
    def type_name(self) -> str:
        return self.value[2]
