"""What happens to a GN packet from the radio: open its security envelope, decode, drop our own, check
plausibility, keep statistics.

Pure logic: fed bytes with the service time, returns the accepted DecodedPacket (or None) and builds the
V2xStatus. Rejections are counted by reason: the security layer's and decoder's RejectReason and the
PlausibilityReason values. A packet the security mode refuses still counts against its station (read
through the envelope without checking it), so the station table shows who is being refused and why.
"""

from __future__ import annotations

from collections import Counter
from dataclasses import dataclass

from coopdrive.services.v2x.config import PlausibilityLimits
from coopdrive.v2x.geonet import GnPacket
from coopdrive.v2x.infrastructure import InfrastructureMessage
from coopdrive.v2x.its_pdu import ItsMessageId
from coopdrive.v2x.mapping.common import optional
from coopdrive.v2x.packet import BeaconPacket, DecodedPacket, V2xPacketCodec, default_codec
from coopdrive.services.v2x.plausibility import Observation, PlausibilityChecker
from coopdrive.v2x.reasons import RejectReason, V2xDecodeError
from coopdrive.v2x.security_verdict import sender_of, verdict_of_opened, verdict_of_refusal
from coopdrive.services.v2x.station_stats import StationStats
from coopdrive.v2x.timebase import MS_PER_S, ItsClock, leap_seconds_since_its_epoch, tai_ms_from_delta
from coopdrive.v2x.units import TENTH_MICRODEG_PER_DEG
from coopdrive.v2x.vru import VruMessage
from coopdrive.v1 import v2x_pb2

# A station silent this long leaves the status (it stays LOST in it until then).
FORGET_AFTER_S = 60.0


@dataclass(frozen=True)
class BeaconPosition:
    latitude_deg: float
    longitude_deg: float
    receive_s: float


@dataclass(frozen=True)
class Heard:
    """What reception made of one packet from the radio, so that nobody reads it again."""

    receive_s: float
    # The sender's GN address (read inside a secured packet's envelope); None when unreadable or a beacon.
    source_mac: bytes | None = None
    decoded: DecodedPacket | None = None  # the packet, when accepted
    transit_delay_s: float | None = None  # a CAM's or iCLCM's, from its generation to reception

    @property
    def generated_s(self) -> float:
        """A CAM's or iCLCM's generation time on our clock (its position and speed were true then, not at
        reception); a DENM's reference time is the event's, so it keeps the reception time."""
        if self.transit_delay_s is None:
            return self.receive_s
        return self.receive_s - max(self.transit_delay_s, 0.0)


@dataclass(frozen=True)
class OwnIdentity:
    mac: bytes
    station_id: int


def source_mac(decoded: DecodedPacket) -> bytes:
    """The GN address MID of the sender's position vector: its MAC address."""
    return bytes(decoded.gn.extended.source_position.address.mid)


def message_time_tai_ms(decoded: DecodedPacket, receive_tai_ms: int) -> int:
    """Generation time (CAM, iCLCM, from generationDeltaTime near the receive time) or DENM reference time."""
    if decoded.message_type == ItsMessageId.DENM:
        return decoded.content.reference_time_tai_ms
    return tai_ms_from_delta(decoded.content.generation_delta_time_ms, receive_tai_ms)


def observation_of(decoded: DecodedPacket, mac: bytes, time_tai_ms: int) -> Observation:
    content = decoded.content
    if decoded.message_type == ItsMessageId.CAM:
        position, hf = content.reference_position, content.high_frequency
        has_hf = content.HasField("high_frequency")
        return Observation(
            mac, decoded.station_id, decoded.message_type, time_tai_ms,
            position.latitude_deg if position.HasField("latitude_deg") else None,
            position.longitude_deg if position.HasField("longitude_deg") else None,
            hf.speed_mps if has_hf and hf.HasField("speed_mps") else None,
            hf.longitudinal_acceleration_mps2 if has_hf and hf.HasField("longitudinal_acceleration_mps2") else None)
    if decoded.message_type == VruMessage.VAM:
        position = content.reference_position
        return Observation(mac, decoded.station_id, decoded.message_type, time_tai_ms,
                           optional(position, "latitude_deg"), optional(position, "longitude_deg"),
                           optional(content, "speed_mps"), optional(content, "longitudinal_acceleration_mps2"))
    if decoded.message_type == ItsMessageId.DENM:
        return Observation(mac, decoded.station_id, decoded.message_type, time_tai_ms,
                           detection_tai_ms=content.detection_time_tai_ms, validity_s=content.validity_duration_s)
    accel = content.target_longitudinal_acceleration_mps2 \
        if content.HasField("target_longitudinal_acceleration_mps2") else None
    return Observation(mac, decoded.station_id, decoded.message_type, time_tai_ms, accel_mps2=accel)


class Reception:
    def __init__(self, own: OwnIdentity, clock: ItsClock, limits: PlausibilityLimits, loss_timeout_s: float,
                 expected_rate_hz: float | None, window_s: float, codec: V2xPacketCodec | None = None,
                 security=None, known_clock_offsets_s: dict[int, float] | None = None):
        self.own = own
        # Stations whose clock is known to run off TAI by a constant (config known_clock_offsets_s): their times are
        # taken back by it before they are judged.
        self.known_clock_offsets_ms = {station: round(offset_s * MS_PER_S)
                                       for station, offset_s in (known_clock_offsets_s or {}).items()}
        # A packet.SecurityLayer: open(packet) -> (unsecured packet, OpenedPacket | None), or V2xDecodeError.
        self.security = security
        self.clock = clock
        self.loss_timeout_s = loss_timeout_s
        self.expected_rate_hz = expected_rate_hz
        self.window_s = window_s
        self.codec = codec or default_codec()
        self.plausibility = PlausibilityChecker(limits, loss_timeout_s)
        self.stations: dict[int, StationStats] = {}
        self.rejected_by_reason: Counter[str] = Counter()
        self.packets_received = 0
        self.own_packets_ignored = 0
        self.beacons_received = 0
        self.beacon_positions: dict[bytes, BeaconPosition] = {}

    def on_packet(self, data: bytes, receive_s: float) -> Heard:
        """What became of the packet: decoded when accepted; not when it was ours, refused, undecodable or
        implausible (counted)."""
        self.packets_received += 1
        try:
            unsecured, opened = self.security.open(data) if self.security is not None else (data, None)
        except V2xDecodeError as error:
            return Heard(receive_s, self._refused_by_security(data, error.reason, receive_s))
        try:
            decoded = self.codec.decode_packet(unsecured)
        except BeaconPacket as beacon:
            self._on_beacon(beacon.gn, receive_s)
            return Heard(receive_s)
        except V2xDecodeError as error:
            self.rejected_by_reason[error.reason.value] += 1
            return Heard(receive_s, sender_of(unsecured, self._unwrap).mac)
        if self.security is not None:
            decoded.security = opened
        mac = source_mac(decoded)
        if mac == self.own.mac or decoded.station_id == self.own.station_id:
            self.own_packets_ignored += 1
            return Heard(receive_s, mac)
        if isinstance(decoded.message_type, InfrastructureMessage):
            return self._on_infrastructure(decoded, mac, receive_s)
        receive_tai_ms = self.clock.tai_ms(receive_s)
        time_tai_ms = message_time_tai_ms(decoded, receive_tai_ms)
        stats = self._stats(decoded.station_id)
        if decoded.message_type != ItsMessageId.DENM:  # a DENM's reference time is its event's, not its sending
            stats.clock.add(time_tai_ms, receive_tai_ms)
            time_tai_ms -= self.known_clock_offsets_ms.get(decoded.station_id, 0)
        # Without a layer of ours the codec's own may have opened the envelope: its result rides on the packet.
        stats.security.add(verdict_of_opened(decoded.security), refused=False)
        reason = self.plausibility.check(observation_of(decoded, mac, time_tai_ms), receive_tai_ms)
        if reason is not None:
            self.rejected_by_reason[reason.value] += 1
            stats.on_rejected(receive_s)
            return Heard(receive_s, mac)
        delay_s = None if decoded.message_type == ItsMessageId.DENM else \
            ItsClock.seconds_between(time_tai_ms, receive_tai_ms)
        stats.on_message(decoded.message_type, receive_s, None if delay_s is None else time_tai_ms, delay_s)
        return Heard(receive_s, mac, decoded, delay_s)

    def _on_infrastructure(self, decoded: DecodedPacket, mac: bytes, receive_s: float) -> Heard:
        """A roadside unit's SPATEM, MAPEM, SREM or SSEM: counted for its station and delivered. They carry no
        generation time to judge a clock by (a minute of the year at most) and no motion to check."""
        stats = self._stats(decoded.station_id)
        stats.security.add(verdict_of_opened(decoded.security), refused=False)
        stats.on_message(decoded.message_type, receive_s, None, None)
        return Heard(receive_s, mac, decoded)

    def _on_beacon(self, gn: GnPacket, receive_s: float) -> None:
        """A beacon names no station id, only its GN address (MAC): its position is kept by MAC."""
        vector = gn.extended.source_position
        mac = bytes(vector.address.mid)
        if mac == self.own.mac:
            self.own_packets_ignored += 1
            return
        self.beacons_received += 1
        self.beacon_positions[mac] = BeaconPosition(vector.latitude_tenth_microdeg / TENTH_MICRODEG_PER_DEG,
                                                    vector.longitude_tenth_microdeg / TENTH_MICRODEG_PER_DEG,
                                                    receive_s)

    def _refused_by_security(self, data: bytes, reason: RejectReason, receive_s: float) -> bytes | None:
        """Counts the refusal against its sender, read through the envelope; returns the sender's MAC."""
        self.rejected_by_reason[reason.value] += 1
        sender = sender_of(data, self._unwrap)
        if sender.station_id is None or sender.mac == self.own.mac or sender.station_id == self.own.station_id:
            return sender.mac
        stats = self._stats(sender.station_id)
        stats.on_rejected(receive_s)
        stats.security.add(verdict_of_refusal(data, reason), refused=True)
        return sender.mac

    def _unwrap(self, packet: bytes) -> bytes | None:
        # Without a layer of our own, the codec's unwrapping one reads the envelope.
        layer = self.security if self.security is not None else self.codec.security
        return layer.verifier.unwrap(packet, count=False).unsecured_packet

    def status(self, now_s: float) -> v2x_pb2.V2xStatus:
        for station_id in [s.station_id for s in self.stations.values()
                           if s.last_seen_s is not None and now_s - s.last_seen_s > FORGET_AFTER_S]:
            del self.stations[station_id]
            self.plausibility.forget(station_id)
        status = v2x_pb2.V2xStatus(packets_received=self.packets_received)
        leap_seconds = leap_seconds_since_its_epoch(self.clock.unix_s(now_s))
        for station_id in sorted(self.stations):
            stats = self.stations[station_id]
            # A station only ever refused by the security mode is listed too (LOST): it is there, and not heard. So is
            # one whose messages are refused as too old or from the future because its clock is off: it says why.
            if stats.last_heard_s is not None or stats.security.refused or stats.clock.is_off():
                status.stations.append(stats.to_proto(now_s, self.loss_timeout_s, leap_seconds))
        for reason, count in sorted(self.rejected_by_reason.items()):
            status.rejected_by_reason[reason] = count
        return status

    def _stats(self, station_id: int) -> StationStats:
        stats = self.stations.get(station_id)
        if stats is None:
            stats = self.stations[station_id] = StationStats(station_id, self.expected_rate_hz, self.window_s)
        return stats
