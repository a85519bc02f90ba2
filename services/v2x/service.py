"""V2X service: GN packets to and from the radio box over UDP; CAM, iCLCM and DENM out; decoded content (those
three and the roadside units' SPATEM, MAPEM, SREM and SSEM), raw packets and per-station link statistics onto the bus.

Socket input only updates state (through ctx.call_soon); everything is published from time triggers.
"""

from __future__ import annotations

import threading
from dataclasses import dataclass
from typing import Callable

from coopdrive.bus import Envelope
from coopdrive.runtime.service import Service
from coopdrive.services.v2x.config import GCDC_RATE_HZ, LinkSync, LinkType, SecurityConfig, V2xConfig
from coopdrive.services.v2x.denm_manager import ActionId
from coopdrive.v2x.infrastructure import InfrastructureCodec, InfrastructureMessage
from coopdrive.v2x.its_pdu import ItsMessageId
from coopdrive.v2x.release2 import release2_spec
from coopdrive.v2x.vru import VruMessage
from coopdrive.v2x.packet import Content, MessageType
from coopdrive.services.v2x.link import CaptureLog, RecordedLink, UdpLink
from coopdrive.services.v2x.pseudonym import PseudonymChanger
from coopdrive.services.v2x.raw_link import RawLink
from coopdrive.services.v2x.reception import OwnIdentity, Reception
from coopdrive.v2x.security.layer import ModeSecurityLayer
from coopdrive.v2x.security.profile import SecurityMode
from coopdrive.v2x.security.signer import SecuredPacketSigner
from coopdrive.v2x.security.store import CertificateStore
from coopdrive.v2x.security.verifier import SecurityVerifier
from coopdrive.services.v2x.security_setup import load_security_material
from coopdrive.v2x.timebase import US_PER_MS, ItsClock
from coopdrive.services.v2x.transmission import Transmitter
from coopdrive.v1 import its_pb2, v2x_pb2

# Source MAC in the pcap for a received packet whose GN header cannot be parsed.
UNKNOWN_MAC = bytes(6)
TOPIC_OF_MESSAGE = {ItsMessageId.CAM: "v2x/cam", ItsMessageId.DENM: "v2x/denm", ItsMessageId.ICLCM: "v2x/iclcm",
                    InfrastructureMessage.SPATEM: "v2x/spatem", InfrastructureMessage.MAPEM: "v2x/mapem",
                    InfrastructureMessage.SREM: "v2x/srem", InfrastructureMessage.SSEM: "v2x/ssem",
                    VruMessage.VAM: "v2x/vam"}


def _compile_port_message_modules() -> None:
    InfrastructureCodec.spec()
    release2_spec()


@dataclass
class _Received:
    receive_s: float
    packet: v2x_pb2.GnPacket
    message_type: MessageType | None = None
    content: Content | None = None
    # When what the message describes was true: a CAM's or iCLCM's generation time, else the reception.
    sample_s: float | None = None


def build_security_layer(config: SecurityConfig, station_id: int, mac: bytes,
                         clock_tai_us) -> ModeSecurityLayer | None:
    """The layer of the configured mode, or None when the mode is off and no PKI is given (today's
    behaviour: unsecured packets only). Our signer keeps the configured station id and MAC (no pseudonym
    change here), since the generators stamp those into every packet."""
    if config.mode is SecurityMode.OFF and config.pki_dir is None:
        return None
    material = load_security_material(config)  # a bad file is one line, before anything starts
    verifier = SecurityVerifier(CertificateStore(trusted_roots=material.roots, authorities=material.authorities))
    signer = SecuredPacketSigner(material.tickets, station_id, mac) if material.tickets else None
    return ModeSecurityLayer(config.mode, verifier, signer, clock_tai_us)


def open_link(config: V2xConfig, on_packet: Callable[[bytes], None]) -> UdpLink | RawLink:
    """The configured link to the air; a raw link that cannot open raises HardwareUnavailable's one line."""
    link = config.link
    if link.type is LinkType.RAW:
        return RawLink(link.interface, config.mac_bytes, on_packet)
    return UdpLink((link.listen_host, link.listen_port), (link.radio_host, link.radio_port), on_packet,
                   link.max_packet_bytes)


class V2xService(Service):
    name = "v2x"
    Config = V2xConfig

    def start(self) -> None:
        c: V2xConfig = self.config
        self.clock = ItsClock(c.clock_epoch_unix_s)
        # Freshness is judged on the ITS clock (sim time + epoch in simulation), as the senders sign with it.
        self.security = build_security_layer(c.security, c.station_id, c.mac_bytes,
                                             lambda: self.clock.tai_ms(self.ctx.now_s()) * US_PER_MS)
        self.transmitter = Transmitter(c, self.clock, security=self.security)
        # The roadside units' and road users' modules compile beside the start (0.3 s of CPU each), not in the
        # first SPATEM's or VAM's reception; one that arrives sooner waits for them.
        threading.Thread(target=_compile_port_message_modules, name="v2x-modules-compile", daemon=True).start()
        self.reception = Reception(OwnIdentity(c.mac_bytes, c.station_id), self.clock, c.plausibility,
                                   c.loss_timeout_s, c.expected_rate_hz, c.statistics_window_s,
                                   security=self.security, known_clock_offsets_s=c.known_clock_offsets_s)
        self.pseudonyms = None
        if c.security.pseudonym_period_s is not None:
            self.pseudonyms = PseudonymChanger(self.security.signer, self.transmitter, self.reception)
            self.ctx.every(c.security.pseudonym_period_s, lambda now_s: self.pseudonyms.request())
        self.packets_sent = 0
        self._received: list[_Received] = []
        # Under replay the recording's own capture is not overwritten, and the radio box is the recording.
        self._capture_file = open(c.pcap_path, "wb") if c.pcap_path and self.ctx.opens_hardware else None
        self.capture = CaptureLog(self._capture_file, c.mac_bytes) if self._capture_file else None
        if not self.ctx.opens_hardware:
            self.link = RecordedLink()
            self.ctx.subscribe("v2x/rx", self.on_recorded_packet, vehicle_id=self.ctx.vehicle_id)
        else:
            self.link = open_link(c, lambda packet: self.ctx.call_soon(lambda: self.on_datagram(packet)))
        self.ctx.subscribe("ego/state", lambda envelope: self.transmitter.on_ego_state(envelope.message))
        self.ctx.subscribe("planner/behaviour", self.on_behaviour)
        self.ctx.subscribe("control/command", self.on_command)
        # The fastest message rate; ETSI CAM rules are checked as often (T_CheckCamGen <= T_GenCamMin).
        self.ctx.every(1.0 / max(c.iclcm_rate_hz, GCDC_RATE_HZ), self.transmit)
        self.ctx.every(c.receive_flush_period_s, self.flush_received)
        self.ctx.every(1.0 / c.status_rate_hz, self.publish_status)
        if not self.ctx.opens_hardware:
            return
        if c.link.sync is LinkSync.MARKS:
            self.ctx.subscribe("radio/mark", self.on_radio_mark)
        else:
            self.link.start()

    def stop(self) -> None:
        link = getattr(self, "link", None)
        if link is not None:
            link.close()
        if getattr(self, "_capture_file", None) is not None:
            self._capture_file.close()
            self._capture_file = None

    # ----- inputs: state updates only ---------------------------------------------------------
    def on_behaviour(self, envelope: Envelope) -> None:
        self.transmitter.on_behaviour(envelope.message)

    def on_command(self, envelope: Envelope) -> None:
        self.transmitter.on_command(envelope.message)

    def on_radio_mark(self, envelope: Envelope) -> None:
        for datagram in self.link.receive_until(envelope.message.written, self.config.link.mark_timeout_s):
            self.on_datagram(datagram)
        self.counters["missing_datagrams"] = self.link.missing_datagrams

    def on_recorded_packet(self, envelope: Envelope) -> None:
        """Replay: a packet the radio box delivered when the drive was recorded."""
        if envelope.message.direction == v2x_pb2.PACKET_DIRECTION_RECEIVED:
            self.on_datagram(envelope.message.payload)

    def on_datagram(self, data: bytes) -> None:
        now_s = self.ctx.now_s()
        heard = self.reception.on_packet(data, now_s)
        mac = heard.source_mac
        if self.capture is not None:
            self.capture.write_packet(data, self.clock.unix_s(now_s), mac or UNKNOWN_MAC)
        received = _Received(now_s, v2x_pb2.GnPacket(direction=v2x_pb2.PACKET_DIRECTION_RECEIVED, payload=data,
                                                     source_mac=mac or b""))
        if heard.decoded is not None:
            received.message_type, received.content = heard.decoded.message_type, heard.decoded.content
            received.sample_s = heard.generated_s
            self.count(f"received_{heard.decoded.message_type.name.lower()}")
        self._received.append(received)

    # DENM API for in-process callers (roadside unit logic, hazard detection).
    def trigger_denm(self, event: its_pb2.DenmContent, repetition_interval_s: float | None = None,
                     repetition_duration_s: float | None = None) -> ActionId:
        return self.transmitter.trigger_denm(event, self.ctx.now_s(), repetition_interval_s, repetition_duration_s)

    def update_denm(self, action: ActionId, event: its_pb2.DenmContent) -> None:
        self.transmitter.update_denm(action, event, self.ctx.now_s())

    def cancel_denm(self, action: ActionId, repetition_duration_s: float = 1.0) -> None:
        self.transmitter.cancel_denm(action, self.ctx.now_s(), repetition_duration_s)

    # ----- time triggers: the only place that publishes -----------------------------------------
    def transmit(self, now_s: float) -> None:
        if self.pseudonyms is not None and self.pseudonyms.change_if_due(now_s):
            self.count("pseudonym_changes")
        for outgoing in self.transmitter.due(now_s):
            if self.capture is not None:
                self.capture.write_packet(outgoing.data, self.clock.unix_s(now_s), self.transmitter.mac)
            if self.link.send(outgoing.data):
                self.packets_sent += 1
                self.count(f"sent_{outgoing.message_type.name.lower()}")
            packet = v2x_pb2.GnPacket(direction=v2x_pb2.PACKET_DIRECTION_SENT, payload=outgoing.data,
                                      source_mac=self.transmitter.mac)
            self.ctx.publish("v2x/tx", packet, sample_time_s=now_s)
        self.counters["encode_errors"] = self.transmitter.encode_errors
        self.counters["seal_errors"] = self.transmitter.seal_errors
        self.counters["send_errors"] = self.link.send_errors
        if self.pseudonyms is not None:
            self.counters["pseudonym_changes_deferred"] = self.pseudonyms.deferred

    def flush_received(self, now_s: float) -> None:
        received, self._received = self._received, []
        for item in received:
            if self.ctx.opens_hardware:
                # What the radio box delivered; under replay it is the recording's, not ours to publish again.
                self.ctx.publish("v2x/rx", item.packet, sample_time_s=item.receive_s)
            if item.content is not None:
                self.ctx.publish(TOPIC_OF_MESSAGE[item.message_type], item.content, sample_time_s=item.sample_s)

    def publish_status(self, now_s: float) -> None:
        status = self.reception.status(now_s)
        status.packets_sent = self.packets_sent
        self.counters["own_packets_ignored"] = self.reception.own_packets_ignored
        self.counters["packets_received"] = self.reception.packets_received
        self.counters["rejected"] = sum(self.reception.rejected_by_reason.values())
        for reason, count in self.reception.rejected_by_reason.items():
            self.counters[f"rejected_{reason}"] = count
        if self.security is not None:
            for name, count in self.security.status.items():
                self.counters[f"security_{name}"] = count
        self.ctx.publish("v2x/status", status, sample_time_s=now_s)
