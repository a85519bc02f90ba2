"""Geolocation service: feeds GNSS fixes, CAN odometry and IMU samples to the Geolocator, publishes the ego state."""

from __future__ import annotations

import enum

from pydantic import BaseModel, ConfigDict, Field, model_validator

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


class LocalOrigin(BaseModel):
    """WGS84 origin of the local ENU frame."""

    model_config = ConfigDict(extra="forbid")

    lat_deg: float = Field(51.4758, ge=-90.0, le=90.0)
    lon_deg: float = Field(5.6247, ge=-180.0, le=180.0)
    alt_m: float = 20.0


class SerialSync(enum.Enum):
    """How the GNSS port's bytes enter the service's step order."""

    # Vehicle (wall clock): a reader thread hands chunks on as they arrive.
    FREE = "free"
    # Simulated clock: read up to each gnss/serial_mark from the simulator, so fixes land at the same step every run.
    MARKS = "marks"


class GeolocationConfig(ServiceConfig):
    geolocator: GeolocatorConfig = GeolocatorConfig()
    # Lane map (a shipped name such as "a270" or a GeoJSON path) for lane matching; its origin is the local frame.
    # None: no lane matching (lane.matched stays false), e.g. the follow world, which lies off every map.
    map_name: str | None = None
    # The local frame's origin, only when there is no map.
    origin: LocalOrigin = LocalOrigin()
    output_rate_hz: float = Field(50.0, gt=0.0)
    use_imu: bool = True
    # GNSS receiver's NMEA serial port; None: the fixes come from the bus topic gnss/fix instead.
    gnss_port: str | None = None
    gnss_baudrate: int = Field(115200, gt=0)
    serial_sync: SerialSync = SerialSync.FREE
    gnss_open_timeout_s: float = Field(10.0, gt=0.0)  # the simulator may create the port after we start
    serial_mark_timeout_s: float = Field(2.0, gt=0.0)
    # A fix is emitted once all these sentences of an epoch arrived (else when the next epoch starts).
    gnss_sentences: frozenset[SentenceType] = frozenset(SentenceType)
    # How long after its epoch the receiver puts a fix on the wire (its datasheet's output latency). A fix is
    # fused at its arrival minus this: left at 0, the estimate trails the car by speed times the latency.
    gnss_receiver_latency_s: float = Field(0.0, ge=0.0)
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
        if self.map_name is not None and self.origin != LocalOrigin():
            raise ValueError("origin is only used without a map: the map brings its own origin")
        if self.geolocator.map_name != GeolocatorConfig().map_name:
            raise ValueError("geolocator.map_name is not read by the service: set map_name instead")
        return self


class GeolocationService(Service):
    name = "geolocation"
    Config = GeolocationConfig

    def start(self) -> None:
        c: GeolocationConfig = self.config
        logic_config = c.geolocator.model_copy(update={"vehicle_id": self.ctx.vehicle_id})
        if c.map_name is not None:
            self.geolocator = Geolocator(logic_config, road_map=RoadMap.load(c.map_name))
        else:
            self.geolocator = Geolocator(logic_config, origin=(c.origin.lat_deg, c.origin.lon_deg, c.origin.alt_m))
        self.serial: GnssSerial | None = None
        if c.gnss_port is None:
            self.ctx.subscribe("gnss/fix", self.on_gnss_fix)
        else:
            self._start_serial(c)
        reader = VehicleBusReader(on_vehicle_state=self.geolocator.on_can_state,
                                  on_imu_sample=self.geolocator.on_imu if c.use_imu else None,
                                  vehicle_state_latency_s=c.can_latency_s, imu_latency_s=c.imu_latency_s,
                                  vehicle_can=c.vehicle_can)
        self.geolocator.configure_odometry(load_adapter(c.vehicle_can)[0].odometry)
        self.vehicle_bus = VehicleBusInput(self.ctx, reader, c.can_port)
        self.ctx.every(1.0 / c.output_rate_hz, self.publish_estimate)

    def _start_serial(self, c: GeolocationConfig) -> None:
        self.decoder = NmeaDecoder(self.on_decoded_fix, expected_sentences=c.gnss_sentences,
                                   receiver_latency_s=c.gnss_receiver_latency_s,
                                   vehicle_id=self.ctx.vehicle_id, sender=self.name)
        self.serial = GnssSerial(c.gnss_port, c.gnss_baudrate, c.gnss_open_timeout_s)
        if c.serial_sync is SerialSync.MARKS:
            self.ctx.subscribe("gnss/serial_mark", self.on_serial_mark)
        else:
            # The reader thread only hands bytes over: decoding runs on the service's worker thread.
            self.serial.start_thread(lambda chunk: self.ctx.call_soon(lambda: self.on_serial_bytes(chunk)))

    def stop(self) -> None:
        self.vehicle_bus.close()
        if self.serial is not None:
            self.serial.close()

    def on_gnss_fix(self, envelope: Envelope) -> None:
        self.geolocator.on_gnss_fix(envelope.message)

    def on_serial_mark(self, envelope: Envelope) -> None:
        if not self.serial.read_until(envelope.message.written, self.config.serial_mark_timeout_s,
                                      self.on_serial_bytes):
            self.count("serial_mark_timeouts")
            self.count("serial_lost_bytes", self.serial.skip_to(envelope.message.written))

    def on_serial_bytes(self, chunk: bytes) -> None:
        self.decoder.feed(chunk, self.ctx.now_s())
        for reason, count in self.decoder.bad.items():
            self.counters[f"nmea_bad_{reason.value}"] = count

    def on_decoded_fix(self, fix: gnss_pb2.GnssFix) -> None:
        self.geolocator.on_gnss_fix(fix)
        # What the receiver said, so recordings hold it next to the estimate.
        self.ctx.publish("ego/gnss", fix, sample_time_s=fix.header.sample_time_s)

    def publish_estimate(self, now_s: float) -> None:
        self.ctx.publish("ego/state", self.geolocator.estimate(now_s), sample_time_s=now_s)
        # stats() are running totals, so they replace the counters rather than add to them.
        self.counters.update(self.geolocator.stats())
        self.counters.update(self.vehicle_bus.counts())
