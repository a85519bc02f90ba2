"""Our DENMs on a live wire, for tests/v2x/live/our_station.py.

The v2x service triggers DENMs only through its in-process API (V2xService.trigger_denm: roadside logic, hazard
detection); no bus topic asks it for one yet. So the harness triggers the event in the service's own Transmitter
(built from the same config: station id, station type, MAC, GN and protocol versions; its CAMs and iCLCMs off, the
service sends those) and puts the sealed packets on the same interface through a RawLink of its own. The service
drops these frames as its own (same source MAC); a peer sees them as our station's DENMs.
"""

from __future__ import annotations

import time

from coopdrive.services.v2x.config import V2xConfig
from coopdrive.services.v2x.raw_link import RawLink
from coopdrive.services.v2x.service import build_security_layer
from coopdrive.v2x.timebase import US_PER_MS, ItsClock
from coopdrive.services.v2x.transmission import Transmitter
from coopdrive.v1 import its_pb2

# A stationary vehicle (ETSI CauseCodeType 94) 50 m north-east of the configured origin, valid for a minute,
# repeated twice a second: the event a peer should decode and keep.
CAUSE_STATIONARY_VEHICLE = 94
EVENT_OFFSET_DEG = 0.0005
VALIDITY_S = 60.0
REPETITION_INTERVAL_S = 0.5


class DenmSender:
    def __init__(self, config: V2xConfig, duration_s: float, now_monotonic_s: float):
        quiet = config.model_copy(update={"send_cam": False, "send_iclcm": False})
        self.clock = ItsClock(config.clock_epoch_unix_s)
        security = build_security_layer(config.security, config.station_id, config.mac_bytes,
                                        lambda: self.clock.tai_ms(time.time()) * US_PER_MS)
        self.transmitter = Transmitter(quiet, self.clock, security=security)
        self.link = RawLink(config.link.interface, config.mac_bytes, lambda _packet: None)
        self.sent = 0
        # The service's clock is unix time when no epoch is configured; the harness paces itself monotonically.
        self._unix_minus_monotonic_s = time.time() - now_monotonic_s
        event = its_pb2.DenmContent(relevance_distance=its_pb2.RELEVANCE_DISTANCE_LESS_THAN_200M,
                                    validity_duration_s=VALIDITY_S)
        event.event_position.latitude_deg = config.origin.lat_deg + EVENT_OFFSET_DEG
        event.event_position.longitude_deg = config.origin.lon_deg + EVENT_OFFSET_DEG
        event.situation.information_quality = 1
        event.situation.event_type.cause_code = CAUSE_STATIONARY_VEHICLE
        self.transmitter.trigger_denm(event, time.time(), REPETITION_INTERVAL_S, duration_s)

    def send_due(self, now_monotonic_s: float) -> None:
        for outgoing in self.transmitter.due(now_monotonic_s + self._unix_minus_monotonic_s):
            self.sent += self.link.send(outgoing.data)

    def close(self) -> None:
        self.link.close()
