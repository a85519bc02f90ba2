"""Our side of the radio: which packets are due now, wrapped in GeoNetworking with the right source position.

Pure logic around the generators and the DENM manager; the service hands the bytes to the UDP link.
"""

from __future__ import annotations

import logging
from dataclasses import dataclass

from coopdrive.services.v2x.config import V2xConfig
from coopdrive.services.v2x.denm_manager import ActionId, DenmManager
from coopdrive.v2x.generation import CamGenerator, IclcmGenerator
from coopdrive.v2x.its_pdu import ItsMessageId
from coopdrive.v2x.packet import DestinationArea, GnParams, SourcePosition, V2xPacketCodec, default_codec
from coopdrive.v2x.security.layer import ModeSecurityLayer
from coopdrive.v2x.timebase import US_PER_MS, ItsClock
from coopdrive.v1 import control_pb2, ego_pb2, its_pb2, planner_pb2

log = logging.getLogger(__name__)

# Geo-broadcast radius of a DENM from its relevance distance (the upper bound of the class).
RADIUS_OF_RELEVANCE_M = {
    its_pb2.RELEVANCE_DISTANCE_LESS_THAN_50M: 50.0,
    its_pb2.RELEVANCE_DISTANCE_LESS_THAN_100M: 100.0,
    its_pb2.RELEVANCE_DISTANCE_LESS_THAN_200M: 200.0,
    its_pb2.RELEVANCE_DISTANCE_LESS_THAN_500M: 500.0,
    its_pb2.RELEVANCE_DISTANCE_LESS_THAN_1000M: 1000.0,
    its_pb2.RELEVANCE_DISTANCE_LESS_THAN_5KM: 5000.0,
    its_pb2.RELEVANCE_DISTANCE_LESS_THAN_10KM: 10000.0,
    its_pb2.RELEVANCE_DISTANCE_OVER_10KM: 65535.0,
}
DEFAULT_DENM_RADIUS_M = 1000.0


@dataclass(frozen=True)
class OutgoingPacket:
    message_type: ItsMessageId
    content: its_pb2.CamContent | its_pb2.DenmContent | its_pb2.IclcmContent
    data: bytes


class Transmitter:
    def __init__(self, config: V2xConfig, clock: ItsClock, codec: V2xPacketCodec | None = None,
                 security: ModeSecurityLayer | None = None):
        self.config = config
        self.clock = clock
        self.codec = codec or default_codec()
        # Seals (signs, per its mode) every packet we send; None: packets go out unsecured.
        self.security = security
        self.cam = CamGenerator(config.cam_mode, config.station_id, config.station_type,
                                config.its_protocol_version, config.origin, config.vehicle)
        self.iclcm = IclcmGenerator(config.station_id, config.vehicle, config.iclcm_rate_hz)
        self.denm = DenmManager(config.station_id, config.station_type, config.its_protocol_version)
        self.encode_errors = 0
        self.seal_errors = 0
        self._sequence_number = 0
        # Our GN source MAC: the configured one until a pseudonym change (use_identity).
        self.mac = config.mac_bytes

    def use_identity(self, station_id: int, mac: bytes) -> None:
        """A new pseudonym: every message from now on carries this station id and MAC."""
        self.cam.station_id = self.iclcm.station_id = self.denm.station_id = station_id
        self.mac = bytes(mac)

    def on_ego_state(self, ego: ego_pb2.EgoState) -> None:
        self.cam.on_ego_state(ego)

    def on_behaviour(self, behaviour: planner_pb2.BehaviourRequest) -> None:
        self.iclcm.on_behaviour(behaviour)

    def on_command(self, command: control_pb2.ControlCommand) -> None:
        self.iclcm.on_command(command)

    def trigger_denm(self, event: its_pb2.DenmContent, now_s: float, repetition_interval_s: float | None = None,
                     repetition_duration_s: float | None = None) -> ActionId:
        return self.denm.trigger(event, now_s, self.clock.tai_ms(now_s), repetition_interval_s, repetition_duration_s)

    def update_denm(self, action: ActionId, event: its_pb2.DenmContent, now_s: float) -> None:
        self.denm.update(action, event, now_s, self.clock.tai_ms(now_s))

    def cancel_denm(self, action: ActionId, now_s: float, repetition_duration_s: float = 1.0) -> None:
        self.denm.cancel(action, now_s, self.clock.tai_ms(now_s), repetition_duration_s)

    def due(self, now_s: float) -> list[OutgoingPacket]:
        tai_ms = self.clock.tai_ms(now_s)
        outgoing: list[OutgoingPacket] = []
        if self.config.send_cam:
            cam = self.cam.generate(now_s, tai_ms)
            if cam is not None:
                self._encode(outgoing, ItsMessageId.CAM, cam, self._params(tai_ms))
        if self.config.send_iclcm:
            iclcm = self.iclcm.generate(now_s, tai_ms)
            if iclcm is not None:
                self._encode(outgoing, ItsMessageId.ICLCM, iclcm, self._params(tai_ms, self._own_position()))
        for denm in self.denm.due(now_s, tai_ms):
            self._encode(outgoing, ItsMessageId.DENM, denm, self._denm_params(denm, tai_ms))
        return outgoing

    def _encode(self, outgoing: list[OutgoingPacket], message_type: ItsMessageId, content, params: GnParams) -> None:
        encode = {ItsMessageId.CAM: self.codec.encode_cam, ItsMessageId.DENM: self.codec.encode_denm,
                  ItsMessageId.ICLCM: self.codec.encode_iclcm}[message_type]
        try:
            data = encode(content, params)
        except (ValueError, KeyError, TypeError) as error:
            # Content the codec cannot put on the wire must not stop the other messages.
            self.encode_errors += 1
            log.warning("cannot encode our %s: %s", message_type.name, error)
            return
        if self.security is not None:
            try:
                # Signed at the packet's own ITS time (the sim clock in simulation), not the system clock.
                data = self.security.seal(data, params.time_tai_ms * US_PER_MS)
            except (ValueError, KeyError, TypeError) as error:
                # An unsigned packet would be dropped by every verifying station: better not sent at all.
                self.seal_errors += 1
                log.warning("cannot sign our %s: %s", message_type.name, error)
                return
        outgoing.append(OutgoingPacket(message_type, content, data))

    def _params(self, tai_ms: int, position: SourcePosition | None = None,
                area: DestinationArea | None = None) -> GnParams:
        c = self.config
        return GnParams(source_mac=self.mac, station_type=c.station_type, gn_version=c.gn_version,
                        time_tai_ms=tai_ms, source_position=position, destination_area=area,
                        sequence_number=self._next_sequence_number() if area is not None else 0)

    def _denm_params(self, denm: its_pb2.DenmContent, tai_ms: int) -> GnParams:
        event = denm.event_position
        radius_m = RADIUS_OF_RELEVANCE_M.get(denm.relevance_distance, DEFAULT_DENM_RADIUS_M)
        area = DestinationArea(event.latitude_deg, event.longitude_deg, radius_m)
        return self._params(tai_ms, self._own_position(), area)

    def _own_position(self) -> SourcePosition:
        ego = self.cam.ego
        if ego is None:
            origin = self.config.origin
            return SourcePosition(origin.lat_deg, origin.lon_deg, position_accurate=False)
        latitude_deg, longitude_deg, _ = self.cam.wgs84(ego)
        return SourcePosition(latitude_deg, longitude_deg, abs(ego.speed_mps), ego.heading_rad)

    def _next_sequence_number(self) -> int:
        self._sequence_number = (self._sequence_number + 1) % 65_536
        return self._sequence_number
