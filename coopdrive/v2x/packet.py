"""One facade for the V2X codec: content message <-> GeoNetworking + BTP-B + UPER bytes.

    packet = encode_cam(cam_content, GnParams(source_mac=..., time_tai_ms=...))
    decoded = decode_packet(packet)          # DecodedPacket, or raises V2xDecodeError(reason)
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from typing import Protocol

from coopdrive.v2x import units
from coopdrive.v2x.btp import BtpBHeader, BtpPort, parse_btp_b
from coopdrive.v2x.geonet import (
    GN_VERSION_GCDC, MAC_SIZE_BYTES, SUPPORTED_GN_VERSIONS, BasicHeader, BeaconHeader, CommonHeader, CommonNextHeader,
    GbcHeader, GeoArea, GeoAreaShape, GnAddress, GnPacket, LongPositionVector, ShbHeader, encode_lifetime, parse_gn)
from coopdrive.v2x.infrastructure import INFRASTRUCTURE_OF_PORT, InfrastructureCodec, InfrastructureMessage
from coopdrive.v2x.its_pdu import ItsCodec, ItsHeader, ItsMessageId, peek_its_header
from coopdrive.v2x.mapping.cam import cam_from_asn, cam_to_asn
from coopdrive.v2x.mapping.denm import denm_from_asn, denm_to_asn
from coopdrive.v2x.mapping.iclcm import iclcm_from_asn, iclcm_to_asn
from coopdrive.v2x.mapping.mapem import mapem_from_asn, mapem_to_asn
from coopdrive.v2x.mapping.spatem import spatem_from_asn, spatem_to_asn
from coopdrive.v2x.mapping.srem import srem_from_asn
from coopdrive.v2x.mapping.ssem import ssem_from_asn
from coopdrive.v2x.mapping.vam import vam_from_asn
from coopdrive.v2x.reasons import RejectReason, V2xDecodeError
from coopdrive.v2x.vru import VRU_OF_PORT, VruCodec, VruMessage
from coopdrive.v1 import infrastructure_pb2, its_pb2

STATION_TYPE_PASSENGER_CAR = 5
PORT_OF_MESSAGE = {ItsMessageId.CAM: BtpPort.CAM, ItsMessageId.DENM: BtpPort.DENM, ItsMessageId.ICLCM: BtpPort.ICLCM}
MESSAGE_OF_PORT = {int(port): message for message, port in PORT_OF_MESSAGE.items()}
_FROM_ASN = {ItsMessageId.CAM: cam_from_asn, ItsMessageId.DENM: denm_from_asn, ItsMessageId.ICLCM: iclcm_from_asn,
             InfrastructureMessage.SPATEM: spatem_from_asn, InfrastructureMessage.MAPEM: mapem_from_asn,
             InfrastructureMessage.SREM: srem_from_asn, InfrastructureMessage.SSEM: ssem_from_asn,
             VruMessage.VAM: vam_from_asn}

Content = its_pb2.CamContent | its_pb2.DenmContent | its_pb2.IclcmContent | infrastructure_pb2.SpatemContent | \
    infrastructure_pb2.MapemContent | infrastructure_pb2.SremContent | infrastructure_pb2.SsemContent | \
    its_pb2.VamContent
# What a decoded packet is: an ITS PDU of its_pdu.py's codec, an infrastructure message of infrastructure.py's or a
# road user's of vru.py's.
MessageType = ItsMessageId | InfrastructureMessage | VruMessage


@dataclass
class SourcePosition:
    """The sender's position for the GeoNetworking long position vector, SI / ENU heading."""

    latitude_deg: float
    longitude_deg: float
    speed_mps: float = 0.0
    heading_rad: float | None = None
    position_accurate: bool = True


@dataclass
class DestinationArea:
    """Geo-broadcast destination; angle_rad is the ENU yaw of the distance_a axis."""

    latitude_deg: float
    longitude_deg: float
    distance_a_m: float
    distance_b_m: float = 0.0
    angle_rad: float = math.pi / 2
    shape: GeoAreaShape = GeoAreaShape.CIRCLE


@dataclass
class GnParams:
    """How to wrap a message: GeoNetworking and BTP settings of the sending station."""

    source_mac: bytes = bytes(MAC_SIZE_BYTES)
    station_type: int = STATION_TYPE_PASSENGER_CAR
    gn_version: int = GN_VERSION_GCDC
    lifetime_s: float = 1.0
    traffic_class: int = 0
    max_hop_limit: int = 1
    # Time of the position vector, TAI ms since 2004 (timebase.tai_ms_from_unix_s).
    time_tai_ms: int = 0
    # None: taken from the CAM's reference position and high-frequency container (CAM only).
    source_position: SourcePosition | None = None
    # None: single-hop broadcast; otherwise geo-broadcast to this area.
    destination_area: DestinationArea | None = None
    sequence_number: int = 0


class SecurityLayer(Protocol):
    """The contract of the codec's security: unwraps (and as it is configured, verifies) secured packets.
    Implemented by security/layer.py's ModeSecurityLayer."""

    def open(self, packet: bytes) -> tuple[bytes, object | None]:
        """(the packet without its security envelope, what the layer found) or raise V2xDecodeError."""


@dataclass(slots=True)
class DecodedFrame:
    """A packet decoded down to the asn1tools dict of its ITS PDU (wire units)."""

    message_type: MessageType
    its_header: ItsHeader
    value: dict
    gn: GnPacket = field(repr=False)
    btp: BtpBHeader = field(repr=False)
    # What the security envelope said (security.inspection.SecurityResult; UNSIGNED when there was none).
    security: object | None = field(default=None, repr=False)

    @property
    def station_id(self) -> int:
        return self.its_header.station_id


@dataclass(slots=True)
class DecodedPacket(DecodedFrame):
    """A decoded frame and its content in SI units."""

    content: Content = field(kw_only=True)


class BeaconPacket(V2xDecodeError):
    """A GN beacon: no message to decode, only the sender's position vector (gn.extended.source_position).

    Raised by decode_frame / decode_packet so that callers expecting a message need no new return type;
    a receiver catches it first and updates what it knows of its neighbours."""

    def __init__(self, gn: GnPacket, security: object | None):
        super().__init__(RejectReason.NOT_BTP_B, "GN beacon")
        self.gn, self.security = gn, security


class V2xPacketCodec:
    """Encodes content messages into GN packets and decodes GN packets into content messages."""

    def __init__(self, its_codec: ItsCodec | None = None, accepted_gn_versions: tuple[int, ...] = SUPPORTED_GN_VERSIONS,
                 security: SecurityLayer | None = None):
        self.its_codec = its_codec or ItsCodec()
        self.infrastructure_codec = InfrastructureCodec()
        self.vru_codec = VruCodec()
        self.accepted_gn_versions = accepted_gn_versions
        # Without one, secured packets are still unwrapped and checked (mode off, no roots, no clock).
        self.security = security if security is not None else _unwrapping_layer()

    def encode_cam(self, content: its_pb2.CamContent, gn_params: GnParams) -> bytes:
        params = gn_params
        if params.source_position is None:
            position, hf = content.reference_position, content.high_frequency
            params = _with_position(params, SourcePosition(
                position.latitude_deg, position.longitude_deg, hf.speed_mps,
                hf.heading_rad if hf.HasField("heading_rad") else None))
        # The CAM and iCLCM mappings clamp every field into range (tests/v2x/test_mapping_ranges.py).
        uper = self.its_codec.encode(ItsMessageId.CAM, cam_to_asn(content), check_ranges=False)
        return self._wrap(ItsMessageId.CAM, uper, params)

    def encode_denm(self, content: its_pb2.DenmContent, gn_params: GnParams) -> bytes:
        return self._wrap(ItsMessageId.DENM, self.its_codec.encode(ItsMessageId.DENM, denm_to_asn(content)),
                          gn_params)

    def encode_iclcm(self, content: its_pb2.IclcmContent, gn_params: GnParams) -> bytes:
        uper = self.its_codec.encode(ItsMessageId.ICLCM, iclcm_to_asn(content), check_ranges=False)
        return self._wrap(ItsMessageId.ICLCM, uper, gn_params)

    def encode_mapem(self, content: infrastructure_pb2.MapemContent, gn_params: GnParams) -> bytes:
        uper = self.infrastructure_codec.encode(InfrastructureMessage.MAPEM, mapem_to_asn(content))
        return self._wrap(InfrastructureMessage.MAPEM, uper, gn_params)

    def encode_spatem(self, content: infrastructure_pb2.SpatemContent, gn_params: GnParams) -> bytes:
        uper = self.infrastructure_codec.encode(InfrastructureMessage.SPATEM, spatem_to_asn(content))
        return self._wrap(InfrastructureMessage.SPATEM, uper, gn_params)

    def decode_packet(self, data: bytes) -> DecodedPacket:
        frame = self.decode_frame(data)
        try:
            content = _FROM_ASN[frame.message_type](frame.value)
        except (ValueError, KeyError, TypeError) as error:
            raise V2xDecodeError(RejectReason.UNMAPPABLE_CONTENT, str(error)) from None
        return DecodedPacket(frame.message_type, frame.its_header, frame.value, frame.gn, frame.btp, frame.security,
                             content=content)

    def decode_frame(self, data: bytes) -> DecodedFrame:
        """GeoNetworking, BTP and UPER decoded; the message still in asn1tools' wire units."""
        data, security = self.security.open(data)
        gn = parse_gn(data, self.accepted_gn_versions)
        if isinstance(gn.extended, BeaconHeader):
            raise BeaconPacket(gn, security)
        if gn.common.next_header != CommonNextHeader.BTP_B:
            raise V2xDecodeError(RejectReason.NOT_BTP_B, f"next header {gn.common.next_header.name}")
        btp, uper = parse_btp_b(gn.payload)
        infrastructure = INFRASTRUCTURE_OF_PORT.get(btp.destination_port)
        if infrastructure is not None:
            its_header = peek_its_header(uper)
            value = self.infrastructure_codec.decode(infrastructure, its_header, uper)
            return DecodedFrame(infrastructure, its_header, value, gn, btp, security)
        vru = VRU_OF_PORT.get(btp.destination_port)
        if vru is not None:
            its_header = peek_its_header(uper)
            return DecodedFrame(vru, its_header, self.vru_codec.decode(vru, its_header, uper), gn, btp, security)
        message_type = MESSAGE_OF_PORT.get(btp.destination_port)
        if message_type is None:
            raise V2xDecodeError(RejectReason.UNKNOWN_BTP_PORT, str(btp.destination_port))
        its_header = peek_its_header(uper)
        if its_header.message_id != message_type:
            raise V2xDecodeError(RejectReason.MESSAGE_ID_PORT_MISMATCH,
                                 f"messageID {its_header.message_id} on port {btp.destination_port}")
        value = self.its_codec.decode_with_header(its_header, uper)
        return DecodedFrame(message_type, its_header, value, gn, btp, security)

    def _wrap(self, message_type: ItsMessageId | InfrastructureMessage, uper: bytes, params: GnParams) -> bytes:
        if params.source_position is None:
            raise ValueError("GnParams.source_position is required for this message type")
        multiplier, base = encode_lifetime(params.lifetime_s)
        basic = BasicHeader(params.gn_version, lifetime_multiplier=multiplier, lifetime_base=base,
                            remaining_hop_limit=params.max_hop_limit)
        common = CommonHeader(traffic_class=params.traffic_class, max_hop_limit=params.max_hop_limit)
        source = _position_vector(params)
        extended: ShbHeader | GbcHeader = ShbHeader(source)
        if params.destination_area is not None:
            area = params.destination_area
            extended = GbcHeader(params.sequence_number, source, GeoArea(
                area.shape, units.LATITUDE_TENTH_MICRODEG.to_wire(area.latitude_deg),
                units.LONGITUDE_TENTH_MICRODEG.to_wire(area.longitude_deg),
                _u16(area.distance_a_m), _u16(area.distance_b_m),
                units.heading_enu_rad_to_etsi_tenth_deg(area.angle_rad) // 10))
        port = message_type.port if isinstance(message_type, InfrastructureMessage) else PORT_OF_MESSAGE[message_type]
        payload = BtpBHeader(port).pack() + uper
        return GnPacket(basic, common, extended, payload).to_bytes()


def _unwrapping_layer() -> SecurityLayer:
    """Security mode off with an empty certificate store: decode everything, verify what can be verified."""
    from coopdrive.v2x.security.layer import ModeSecurityLayer
    from coopdrive.v2x.security.profile import SecurityMode
    from coopdrive.v2x.security.store import CertificateStore
    from coopdrive.v2x.security.verifier import SecurityVerifier

    return ModeSecurityLayer(SecurityMode.OFF, SecurityVerifier(CertificateStore()), clock_tai_us=None)


def _with_position(params: GnParams, position: SourcePosition) -> GnParams:
    return GnParams(**{**params.__dict__, "source_position": position})


def _u16(value: float) -> int:
    return min(max(round(value), 0), 0xFFFF)


def _position_vector(params: GnParams) -> LongPositionVector:
    position = params.source_position
    heading = units.heading_enu_rad_to_etsi_tenth_deg(position.heading_rad)
    return LongPositionVector(
        GnAddress(station_type=params.station_type, mid=bytes(params.source_mac)),
        params.time_tai_ms, units.LATITUDE_TENTH_MICRODEG.to_wire(position.latitude_deg),
        units.LONGITUDE_TENTH_MICRODEG.to_wire(position.longitude_deg), position.position_accurate,
        units.GN_SPEED_CMPS.to_wire(position.speed_mps),
        0 if heading == units.HEADING_UNAVAILABLE_TENTH_DEG else heading)


_default: V2xPacketCodec | None = None


def default_codec() -> V2xPacketCodec:
    global _default
    if _default is None:
        _default = V2xPacketCodec()
    return _default


def encode_cam(content: its_pb2.CamContent, gn_params: GnParams) -> bytes:
    return default_codec().encode_cam(content, gn_params)


def encode_denm(content: its_pb2.DenmContent, gn_params: GnParams) -> bytes:
    return default_codec().encode_denm(content, gn_params)


def encode_iclcm(content: its_pb2.IclcmContent, gn_params: GnParams) -> bytes:
    return default_codec().encode_iclcm(content, gn_params)


def decode_packet(data: bytes) -> DecodedPacket:
    return default_codec().decode_packet(data)
