"""Geolocation service: feeds GNSS fixes, CAN odometry and IMU samples to the Geolocator, publishes the ego state."""

from __future__ import annotations

from coopdrive.bus import Envelope
from coopdrive.can.adapter import load_adapter
from coopdrive.can.bus_input import VehicleBusInput
from coopdrive.can.bus_reader import VehicleBusReader
from coopdrive.roadmap import RoadMap
from coopdrive.runtime.service import Service
from coopdrive.services.geolocation.config import GeolocationConfig, GnssInput, SerialSync
from coopdrive.services.geolocation.geolocator import Geolocator
from coopdrive.services.geolocation.gnss_serial import GnssSerial
from coopdrive.gnss.nmea_decoder import NmeaDecoder
from coopdrive.v1 import gnss_pb2
from coopdrive.vehicle import vehicle_of

__all__ = ["GeolocationConfig", "GeolocationService", "GnssInput", "SerialSync", "gnss_sources"]


def gnss_sources(config: GeolocationConfig, opens_hardware: bool) -> set[GnssInput]:
    """The GNSS inputs a service reads: under replay the port's recorded chunks stand in for the port."""
    if config.gnss_input is GnssInput.AUTO:
        sources = {GnssInput.PORT} if config.gnss_port is not None else {GnssInput.NMEA_TOPIC, GnssInput.FIX_TOPIC}
    else:
        sources = {config.gnss_input}
    if GnssInput.PORT in sources and not opens_hardware:
        sources = {GnssInput.NMEA_TOPIC}
    return sources


class GeolocationService(Service):
    name = "geolocation"
    Config = GeolocationConfig

    def start(self) -> None:
        c: GeolocationConfig = self.config
        self.serial: GnssSerial | None = None
        self.vehicle_bus: VehicleBusInput | None = None
        self._far_fix_logged = False
        logic_config = c.geolocator.model_copy(update={"vehicle_id": self.ctx.vehicle_id})
        adapter = load_adapter(c.vehicle_can)[0]
        car = {"vehicle": vehicle_of(c.vehicle), "antenna": adapter.mounting.gnss_antenna}
        if c.map_name is not None:
            self.geolocator = Geolocator(logic_config, road_map=RoadMap.load(c.map_name), **car)
        elif c.origin is not None:
            self.geolocator = Geolocator(logic_config, origin=(c.origin.lat_deg, c.origin.lon_deg, c.origin.alt_m),
                                         **car)
        else:
            self.geolocator = Geolocator(logic_config, first_fix_origin=True, **car)
        self.decoder = NmeaDecoder(self.on_decoded_fix, expected_sentences=c.gnss_sentences,
                                   receiver_latency_s=c.gnss_receiver_latency_s,
                                   vehicle_id=self.ctx.vehicle_id, sender=self.name)
        sources = gnss_sources(c, getattr(self.ctx, "opens_hardware", True))
        if GnssInput.FIX_TOPIC in sources:
            self.ctx.subscribe("gnss/fix", self.on_gnss_fix)
        if GnssInput.NMEA_TOPIC in sources:
            self.ctx.subscribe("gnss/nmea", self.on_nmea_chunk)
        if GnssInput.PORT in sources:
            self._start_serial(c)
        reader = VehicleBusReader(on_vehicle_state=self.geolocator.on_can_state,
                                  on_imu_sample=self.geolocator.on_imu if c.use_imu else None,
                                  vehicle_state_latency_s=c.can_latency_s, imu_latency_s=c.imu_latency_s,
                                  vehicle_can=c.vehicle_can)
        self.geolocator.configure_odometry(adapter.odometry)
        self.vehicle_bus = VehicleBusInput(self.ctx, reader, c.can_port)
        self.ctx.every(1.0 / c.output_rate_hz, self.publish_estimate)

    def _start_serial(self, c: GeolocationConfig) -> None:
        self.serial = GnssSerial(c.gnss_port, c.gnss_baudrate, c.gnss_open_timeout_s, log=self.ctx.log)
        if c.serial_sync is SerialSync.MARKS:
            self.ctx.subscribe("gnss/serial_mark", self.on_serial_mark)
        else:
            # Stamped on the reader thread, when the bytes arrived; decoded on the service's worker thread.
            self.serial.start_thread(self._on_arrival)

    def _on_arrival(self, chunk: bytes) -> None:
        arrival_s = self.ctx.now_s()
        self.ctx.call_soon(lambda: self.on_serial_bytes(chunk, arrival_s))

    def stop(self) -> None:
        # Safe after a start that failed half way (a port that could not be opened).
        if getattr(self, "vehicle_bus", None) is not None:
            self._update_counters()  # the final counts (a replay prints them)
            self.vehicle_bus.close()
        if getattr(self, "serial", None) is not None:
            self.serial.close()

    def on_gnss_fix(self, envelope: Envelope) -> None:
        self._to_geolocator(envelope.message)

    def on_serial_mark(self, envelope: Envelope) -> None:
        if not self.serial.read_until(envelope.message.written, self.config.serial_mark_timeout_s,
                                      self.on_serial_bytes):
            self.count("serial_mark_timeouts")
            self.count("serial_lost_bytes", self.serial.skip_to(envelope.message.written))

    def on_serial_bytes(self, chunk: bytes, arrival_s: float | None = None) -> None:
        """Bytes from the port: onto the bus as they came (so a recording can replay them), then decoded."""
        arrival_s = self.ctx.now_s() if arrival_s is None else arrival_s
        self.ctx.publish("gnss/nmea", gnss_pb2.NmeaChunk(data=chunk, port=self.config.gnss_port),
                         sample_time_s=arrival_s)
        self._decode(chunk, arrival_s)

    def on_nmea_chunk(self, envelope: Envelope) -> None:
        chunk: gnss_pb2.NmeaChunk = envelope.message
        self._decode(chunk.data, chunk.header.sample_time_s)

    def _decode(self, data: bytes, arrival_s: float) -> None:
        self.decoder.feed(data, arrival_s)
        self.counters.update(self.decoder.counts())

    def on_decoded_fix(self, fix: gnss_pb2.GnssFix) -> None:
        self._to_geolocator(fix)
        # What the receiver said, so recordings hold it next to the estimate.
        self.ctx.publish("ego/gnss", fix, sample_time_s=fix.header.sample_time_s)

    def _to_geolocator(self, fix: gnss_pb2.GnssFix) -> None:
        had_origin = self.geolocator.origin is not None
        self.geolocator.on_gnss_fix(fix)
        if not had_origin and self.geolocator.origin is not None:
            self.ctx.log.info("geolocation: local frame origin at the first fix, %.7f, %.7f, %.2f m",
                              *self.geolocator.origin)
        distance_m = self.geolocator.far_fix_distance_m
        if distance_m is not None and not self._far_fix_logged:
            self._far_fix_logged = True
            lat, lon, _ = self.geolocator.origin
            self.ctx.log.error("geolocation: fixes at %.5f, %.5f are %.0f km from the local frame's origin "
                               "%.5f, %.5f: refused (set origin near the drive, or leave it unset to take the "
                               "first fix's)", fix.latitude_deg, fix.longitude_deg, distance_m / 1000.0, lat, lon)

    def publish_estimate(self, now_s: float) -> None:
        self.decoder.flush_stale(now_s, self.config.gnss_epoch_wait_s)
        self.ctx.publish("ego/state", self.geolocator.estimate(now_s), sample_time_s=now_s)
        self._update_counters()

    def _update_counters(self) -> None:
        # stats() are running totals, so they replace the counters rather than add to them.
        self.counters.update(self.geolocator.stats())
        self.counters.update(self.vehicle_bus.counts())
        if self.serial is not None:
            self.counters.update(self.serial.counters)
