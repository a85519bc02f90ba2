"""Geolocation service: feeds GNSS fixes, CAN odometry and IMU samples to the Geolocator, publishes the ego state."""

from __future__ import annotations

import enum

from pydantic import Field, model_validator

from coopdrive.geodesy import GeodeticOrigin
from coopdrive.bus import Envelope
from coopdrive.can.adapter import VehicleCanPath, load_adapter
from coopdrive.can.bus_input import VehicleBusInput
from coopdrive.can.bus_reader import VehicleBusReader
from coopdrive.can.vehicle_port import VehicleCanPortConfig
from coopdrive.roadmap import RoadMap
from coopdrive.runtime.service import Service, ServiceConfig
from coopdrive.services.geolocation.config import GeolocatorConfig
from coopdrive.services.geolocation.geolocator import Geolocator
from coopdrive.services.geolocation.gnss_serial import GnssSerial
from coopdrive.services.geolocation.nmea_decoder import NmeaDecoder, SentenceType
from coopdrive.v1 import gnss_pb2
from coopdrive.vehicle import VehicleKind, vehicle_of


class GnssInput(enum.Enum):
    """Where the GNSS data come from."""

    # The port when gnss_port is set, else whichever of gnss/nmea (an imported log, another driver) and
    # gnss/fix (the simulator) the bus carries.
    AUTO = "auto"
    # gnss_port (under replay, which opens no hardware: the gnss/nmea chunks the port delivered when recorded).
    PORT = "port"
    # NMEA bytes on the gnss/nmea topic, decoded here.
    NMEA_TOPIC = "nmea_topic"
    # Decoded fixes on the gnss/fix topic.
    FIX_TOPIC = "fix_topic"


class SerialSync(enum.Enum):
    """How the GNSS port's bytes enter the service's step order."""

    # Vehicle (wall clock): a reader thread hands chunks on as they arrive.
    FREE = "free"
    # Simulated clock: read up to each gnss/serial_mark from the simulator, so fixes land at the same step every run.
    MARKS = "marks"


class GeolocationConfig(ServiceConfig):
    # The vehicle whose geometry the motion model and the odometry take (where geolocator leaves it open).
    vehicle: VehicleKind = VehicleKind.PASSENGER_CAR
    geolocator: GeolocatorConfig = GeolocatorConfig()
    # Lane map (a shipped name such as "a270" or a GeoJSON path) for lane matching; its origin is the local frame.
    # None: no lane matching (lane.matched stays false), e.g. a road no map holds.
    map_name: str | None = None
    # The local frame's origin, only when there is no map; None: the first fix's position (logged).
    origin: GeodeticOrigin | None = None
    output_rate_hz: float = Field(50.0, gt=0.0)
    use_imu: bool = True
    gnss_input: GnssInput = GnssInput.AUTO
    # The GNSS receiver's NMEA port: a device or a pyserial URL (socket://host:port, rfc2217://host:port).
    # Every chunk read from it is published on gnss/nmea, stamped on arrival, and decoded from that stream.
    gnss_port: str | None = None
    gnss_baudrate: int = Field(115200, gt=0)
    serial_sync: SerialSync = SerialSync.FREE
    gnss_open_timeout_s: float = Field(10.0, gt=0.0)  # the simulator may create the port after we start
    serial_mark_timeout_s: float = Field(2.0, gt=0.0)
    # A fix is emitted once all these sentences of an epoch arrived (else when the next epoch starts).
    gnss_sentences: frozenset[SentenceType] = frozenset(
        {SentenceType.GGA, SentenceType.RMC, SentenceType.GST, SentenceType.VTG})
    # How long after its epoch the receiver puts a fix on the wire (its datasheet's output latency). A fix is
    # fused at its arrival minus this: left at 0, the estimate trails the car by speed times the latency.
    gnss_receiver_latency_s: float = Field(0.0, ge=0.0)
    # An epoch with a position still lacking some sentence this long after its first one is emitted anyway.
    gnss_epoch_wait_s: float = Field(0.5, gt=0.0)
    # The vehicle's CAN bus (python-can) with the VEH_ odometry frames; None: the frames come from the
    # can/vehicle topic (simulation, replay).
    can_port: VehicleCanPortConfig | None = None
    # The car's vehicle CAN adapter (coopdrive/can/adapter.py): where its bus carries wheel speeds, yaw rate,
    # steering; None: the simulator's car.
    vehicle_can: VehicleCanPath = None
    # How long after measuring them the car puts wheel speeds and yaw rate on the bus, and the IMU its samples.
    can_latency_s: float = Field(0.005, ge=0.0)
    imu_latency_s: float = Field(0.005, ge=0.0)

    @model_validator(mode="after")
    def _one_source_of_the_frame(self) -> GeolocationConfig:
        # Compared by value, not by which keys were given, so a recorded full config loads again.
        if self.map_name is not None and self.origin is not None:
            raise ValueError("origin is only used without a map: the map brings its own origin")
        if self.gnss_input is GnssInput.PORT and self.gnss_port is None:
            raise ValueError("gnss_input: port needs gnss_port")
        if self.geolocator.map_name != GeolocatorConfig().map_name:
            raise ValueError("geolocator.map_name is not read by the service: set map_name instead")
        return self


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
        vehicle = vehicle_of(c.vehicle)
        if c.map_name is not None:
            self.geolocator = Geolocator(logic_config, road_map=RoadMap.load(c.map_name), vehicle=vehicle)
        elif c.origin is not None:
            self.geolocator = Geolocator(logic_config, origin=(c.origin.lat_deg, c.origin.lon_deg, c.origin.alt_m),
                                         vehicle=vehicle)
        else:
            self.geolocator = Geolocator(logic_config, first_fix_origin=True, vehicle=vehicle)
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
        self.geolocator.configure_odometry(load_adapter(c.vehicle_can)[0].odometry)
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
        # stats() are running totals, so they replace the counters rather than add to them.
        self.counters.update(self.geolocator.stats())
        self.counters.update(self.vehicle_bus.counts())
        if self.serial is not None:
            self.counters.update(self.serial.counters)
