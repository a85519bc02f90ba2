from coopdrive.v1 import header_pb2 as _header_pb2
from google.protobuf.internal import containers as _containers
from google.protobuf.internal import enum_type_wrapper as _enum_type_wrapper
from google.protobuf import descriptor as _descriptor
from google.protobuf import message as _message
from collections.abc import Iterable as _Iterable, Mapping as _Mapping
from typing import ClassVar as _ClassVar, Optional as _Optional, Union as _Union

DESCRIPTOR: _descriptor.FileDescriptor

class PacketDirection(int, metaclass=_enum_type_wrapper.EnumTypeWrapper):
    __slots__ = ()
    PACKET_DIRECTION_UNSPECIFIED: _ClassVar[PacketDirection]
    PACKET_DIRECTION_RECEIVED: _ClassVar[PacketDirection]
    PACKET_DIRECTION_SENT: _ClassVar[PacketDirection]

class LinkState(int, metaclass=_enum_type_wrapper.EnumTypeWrapper):
    __slots__ = ()
    LINK_STATE_UNSPECIFIED: _ClassVar[LinkState]
    LINK_STATE_ACTIVE: _ClassVar[LinkState]
    LINK_STATE_LOST: _ClassVar[LinkState]
PACKET_DIRECTION_UNSPECIFIED: PacketDirection
PACKET_DIRECTION_RECEIVED: PacketDirection
PACKET_DIRECTION_SENT: PacketDirection
LINK_STATE_UNSPECIFIED: LinkState
LINK_STATE_ACTIVE: LinkState
LINK_STATE_LOST: LinkState

class GnPacket(_message.Message):
    __slots__ = ("header", "direction", "payload", "source_mac")
    HEADER_FIELD_NUMBER: _ClassVar[int]
    DIRECTION_FIELD_NUMBER: _ClassVar[int]
    PAYLOAD_FIELD_NUMBER: _ClassVar[int]
    SOURCE_MAC_FIELD_NUMBER: _ClassVar[int]
    header: _header_pb2.Header
    direction: PacketDirection
    payload: bytes
    source_mac: bytes
    def __init__(self, header: _Optional[_Union[_header_pb2.Header, _Mapping]] = ..., direction: _Optional[_Union[PacketDirection, str]] = ..., payload: _Optional[bytes] = ..., source_mac: _Optional[bytes] = ...) -> None: ...

class StationLinkStats(_message.Message):
    __slots__ = ("station_id", "state", "last_heard_s", "message_rate_hz", "reception_ratio", "update_delay_p50_s", "update_delay_p95_s", "update_delay_max_s", "messages_received", "messages_rejected", "trust", "signed", "verified", "trusted", "messages_signed", "messages_verified", "messages_trusted", "signature_failures", "messages_refused_by_security", "last_security_reason", "messages_untrusted", "periodic_received_total", "periodic_expected_total")
    STATION_ID_FIELD_NUMBER: _ClassVar[int]
    STATE_FIELD_NUMBER: _ClassVar[int]
    LAST_HEARD_S_FIELD_NUMBER: _ClassVar[int]
    MESSAGE_RATE_HZ_FIELD_NUMBER: _ClassVar[int]
    RECEPTION_RATIO_FIELD_NUMBER: _ClassVar[int]
    UPDATE_DELAY_P50_S_FIELD_NUMBER: _ClassVar[int]
    UPDATE_DELAY_P95_S_FIELD_NUMBER: _ClassVar[int]
    UPDATE_DELAY_MAX_S_FIELD_NUMBER: _ClassVar[int]
    MESSAGES_RECEIVED_FIELD_NUMBER: _ClassVar[int]
    MESSAGES_REJECTED_FIELD_NUMBER: _ClassVar[int]
    TRUST_FIELD_NUMBER: _ClassVar[int]
    SIGNED_FIELD_NUMBER: _ClassVar[int]
    VERIFIED_FIELD_NUMBER: _ClassVar[int]
    TRUSTED_FIELD_NUMBER: _ClassVar[int]
    MESSAGES_SIGNED_FIELD_NUMBER: _ClassVar[int]
    MESSAGES_VERIFIED_FIELD_NUMBER: _ClassVar[int]
    MESSAGES_TRUSTED_FIELD_NUMBER: _ClassVar[int]
    SIGNATURE_FAILURES_FIELD_NUMBER: _ClassVar[int]
    MESSAGES_REFUSED_BY_SECURITY_FIELD_NUMBER: _ClassVar[int]
    LAST_SECURITY_REASON_FIELD_NUMBER: _ClassVar[int]
    MESSAGES_UNTRUSTED_FIELD_NUMBER: _ClassVar[int]
    PERIODIC_RECEIVED_TOTAL_FIELD_NUMBER: _ClassVar[int]
    PERIODIC_EXPECTED_TOTAL_FIELD_NUMBER: _ClassVar[int]
    station_id: int
    state: LinkState
    last_heard_s: float
    message_rate_hz: float
    reception_ratio: float
    update_delay_p50_s: float
    update_delay_p95_s: float
    update_delay_max_s: float
    messages_received: int
    messages_rejected: int
    trust: float
    signed: bool
    verified: bool
    trusted: bool
    messages_signed: int
    messages_verified: int
    messages_trusted: int
    signature_failures: int
    messages_refused_by_security: int
    last_security_reason: str
    messages_untrusted: int
    periodic_received_total: int
    periodic_expected_total: int
    def __init__(self, station_id: _Optional[int] = ..., state: _Optional[_Union[LinkState, str]] = ..., last_heard_s: _Optional[float] = ..., message_rate_hz: _Optional[float] = ..., reception_ratio: _Optional[float] = ..., update_delay_p50_s: _Optional[float] = ..., update_delay_p95_s: _Optional[float] = ..., update_delay_max_s: _Optional[float] = ..., messages_received: _Optional[int] = ..., messages_rejected: _Optional[int] = ..., trust: _Optional[float] = ..., signed: _Optional[bool] = ..., verified: _Optional[bool] = ..., trusted: _Optional[bool] = ..., messages_signed: _Optional[int] = ..., messages_verified: _Optional[int] = ..., messages_trusted: _Optional[int] = ..., signature_failures: _Optional[int] = ..., messages_refused_by_security: _Optional[int] = ..., last_security_reason: _Optional[str] = ..., messages_untrusted: _Optional[int] = ..., periodic_received_total: _Optional[int] = ..., periodic_expected_total: _Optional[int] = ...) -> None: ...

class V2xStatus(_message.Message):
    __slots__ = ("header", "stations", "rejected_by_reason", "packets_sent", "packets_received")
    class RejectedByReasonEntry(_message.Message):
        __slots__ = ("key", "value")
        KEY_FIELD_NUMBER: _ClassVar[int]
        VALUE_FIELD_NUMBER: _ClassVar[int]
        key: str
        value: int
        def __init__(self, key: _Optional[str] = ..., value: _Optional[int] = ...) -> None: ...
    HEADER_FIELD_NUMBER: _ClassVar[int]
    STATIONS_FIELD_NUMBER: _ClassVar[int]
    REJECTED_BY_REASON_FIELD_NUMBER: _ClassVar[int]
    PACKETS_SENT_FIELD_NUMBER: _ClassVar[int]
    PACKETS_RECEIVED_FIELD_NUMBER: _ClassVar[int]
    header: _header_pb2.Header
    stations: _containers.RepeatedCompositeFieldContainer[StationLinkStats]
    rejected_by_reason: _containers.ScalarMap[str, int]
    packets_sent: int
    packets_received: int
    def __init__(self, header: _Optional[_Union[_header_pb2.Header, _Mapping]] = ..., stations: _Optional[_Iterable[_Union[StationLinkStats, _Mapping]]] = ..., rejected_by_reason: _Optional[_Mapping[str, int]] = ..., packets_sent: _Optional[int] = ..., packets_received: _Optional[int] = ...) -> None: ...
