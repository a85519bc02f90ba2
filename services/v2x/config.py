"""Configuration of the v2x service (units in the field names)."""

from __future__ import annotations

import enum
from datetime import datetime
from pathlib import Path

from pydantic import BaseModel, ConfigDict, Field, field_validator, model_validator

from coopdrive.geodesy import GeodeticOrigin
from coopdrive.runtime.service import ServiceConfig
from coopdrive.v2x.generation import GCDC_RATE_HZ, CamMode, VehicleDimensions
from coopdrive.v2x.geonet import MAC_SIZE_BYTES, SUPPORTED_GN_VERSIONS
from coopdrive.v2x.profile import PROFILE_DEFAULTS, V2xProfile
from coopdrive.v2x.security.profile import SecurityMode
from coopdrive.v1 import its_pb2

class _Section(BaseModel):
    model_config = ConfigDict(extra="forbid")


class LinkSync(enum.Enum):
    # A reader thread takes datagrams as they come (the vehicle).
    FREE = "free"
    # The simulated radio box publishes radio/mark with how many datagrams it has sent us; each mark is
    # read up to in step order, so lockstep runs stay deterministic.
    MARKS = "marks"


class LinkType(enum.Enum):
    # UDP to a radio box that forwards GN packets as datagrams (and the simulator's radio).
    UDP = "udp"
    # GN frames straight on a network interface (802.11p OCB, a Cohda-style box's Linux interface): AF_PACKET.
    RAW = "raw"


class RadioLinkConfig(_Section):
    """How GN packets reach the air. udp: a radio box sends us raw GN packets on listen_port and takes ours on its
    port. raw: frames with ethertype 0x8947 on `interface` (needs CAP_NET_RAW)."""

    type: LinkType = LinkType.UDP
    interface: str | None = None
    sync: LinkSync = LinkSync.FREE
    # How long a mark may wait for its datagrams before they are counted missing.
    mark_timeout_s: float = Field(2.0, gt=0)

    radio_host: str = "127.0.0.1"
    radio_port: int = Field(4400, ge=1, le=65535)
    listen_host: str = "127.0.0.1"
    # 0: any free port (tests).
    listen_port: int = Field(4401, ge=0, le=65535)
    max_packet_bytes: int = Field(2048, gt=0)

    @model_validator(mode="after")
    def _raw_needs_an_interface(self) -> "RadioLinkConfig":
        if self.type is LinkType.RAW and not self.interface:
            raise ValueError("link: type raw needs the network interface, e.g. interface: wlan0")
        if self.type is LinkType.RAW and self.sync is LinkSync.MARKS:
            raise ValueError("link: sync marks is the simulated radio box's; a raw link reads freely")
        return self


class PlausibilityLimits(_Section):
    max_speed_mps: float = Field(70.0, gt=0.0)
    max_accel_mps2: float = Field(15.0, gt=0.0)
    # Position noise allowed on top of max_speed_mps * dt between two CAMs of a station.
    position_jump_tolerance_m: float = Field(5.0, ge=0.0)
    # Speed noise allowed on top of max_accel_mps2 * dt.
    speed_jump_tolerance_mps: float = Field(2.0, ge=0.0)
    max_age_s: float = Field(1.0, gt=0.0)
    max_future_s: float = Field(0.2, ge=0.0)


class SecurityConfig(_Section):
    """TS 103 097 envelope of our packets: the mode, the PKI written by `coopdrive pki init`, our ticket."""

    mode: SecurityMode = SecurityMode.OFF
    # Directory of root.cert and aa.cert (trusted root, known authority) and vehicles/NAME/ticket-K.*.
    pki_dir: Path | None = None
    # The vehicle name under pki_dir/vehicles whose tickets this station signs with.
    ticket: str | None = None
    # More root certificates (files) to trust besides pki_dir/root.cert, and the authorities under them.
    extra_trusted_roots: list[Path] = []
    extra_authorities: list[Path] = []
    # Change pseudonym (next ticket, random station id and MAC) this often; None: keep the configured identity.
    # A change falling due during a manoeuvre waits until it is over.
    pseudonym_period_s: float | None = Field(None, gt=0)

    @model_validator(mode="after")
    def _pki_holds_what_the_mode_needs(self) -> "SecurityConfig":
        if self.pki_dir is None:
            if self.mode is not SecurityMode.OFF:
                raise ValueError(f"security.pki_dir is required in security.mode {self.mode.value}")
            if self.ticket is not None:
                raise ValueError("security.ticket needs a security.pki_dir")
        else:
            for name in ("root.cert", "aa.cert"):
                if not (self.pki_dir / name).is_file():
                    raise ValueError(f"security.pki_dir {self.pki_dir} holds no {name} (coopdrive pki init DIR)")
        if self.mode.signs and self.ticket is None:
            raise ValueError(f"security.ticket is required in security.mode {self.mode.value}")
        if self.ticket is not None and not any((self.pki_dir / "vehicles" / self.ticket).glob("ticket-*.cert")):
            raise ValueError(f"security.ticket {self.ticket!r}: {self.pki_dir}/vehicles holds no tickets for it")
        if self.pseudonym_period_s is not None and not self.mode.signs:
            raise ValueError(f"security.pseudonym_period_s needs a signing security.mode, not {self.mode.value}")
        for root in self.extra_trusted_roots:
            if not root.is_file():
                raise ValueError(f"security.extra_trusted_roots: no file {root}")
        return self


class V2xConfig(ServiceConfig):
    link: RadioLinkConfig = RadioLinkConfig()
    # Source MAC of our GN packets ("02:00:00:00:00:01"); also how our own looped-back packets are recognised.
    vehicle_mac: str = "02:00:00:00:00:01"
    station_id: int = Field(1001, ge=0, le=2**32 - 1)
    # ETSI StationType: a code (5) or a name ("passenger_car", "road_side_unit").
    station_type: int = its_pb2.STATION_TYPE_PASSENGER_CAR
    # What the station speaks (coopdrive/v2x/profile.py): etsi, as today's stations do, or gcdc (GCDC 2016). It
    # sets the next three where they are not set themselves (and so the expected CAM rate).
    profile: V2xProfile = V2xProfile.ETSI
    gn_version: int = PROFILE_DEFAULTS[V2xProfile.ETSI].gn_version
    # ItsPduHeader.protocolVersion of CAM and DENM (1 GCDC, 2 current); the iCLCM is always 1.
    its_protocol_version: int = Field(PROFILE_DEFAULTS[V2xProfile.ETSI].its_protocol_version, ge=1, le=2)
    cam_mode: CamMode = PROFILE_DEFAULTS[V2xProfile.ETSI].cam_mode
    send_cam: bool = True
    send_iclcm: bool = True
    # Every packet sent and received, as Ethernet frames (ethertype 0x8947); None: no capture.
    pcap_path: str | None = None
    # The local ENU frame's origin, used when an EgoState carries no latitude/longitude.
    origin: GeodeticOrigin = GeodeticOrigin()
    vehicle: VehicleDimensions = VehicleDimensions()
    # The service clock plus this instant is UTC. None: the clock already is unix time (the wall clock);
    # in simulation give the UTC instant of sim time 0, e.g. "2016-05-28T10:00:00Z".
    clock_epoch_utc: datetime | None = None
    loss_timeout_s: float = Field(0.4, gt=0.0)
    # Rate at which every remote station's CAMs and iCLCMs are expected, for the reception ratio. Unset: the
    # cam_mode's (gcdc: 25 Hz); with cam_mode etsi, each station's own (coopdrive/v2x/expected_period.py),
    # since EN 302 637-2 lets a CAM come every 100-1000 ms as the sender's dynamics trigger it.
    expected_rate_hz: float | None = Field(None, gt=0.0)
    statistics_window_s: float = Field(5.0, gt=0.0)
    # Stations whose clock is known to run a constant off TAI, in seconds (negative: behind), by station id: their
    # generation times are taken back by it before they are judged fresh. E.g. {3001: -5.0} for a peer that stamps
    # UTC since 2004 without the leap seconds. The station table shows every station's measured clock_offset_s.
    known_clock_offsets_s: dict[int, float] = {}
    status_rate_hz: float = Field(5.0, gt=0.0)
    iclcm_rate_hz: float = Field(GCDC_RATE_HZ, gt=0.0)
    # How often received packets are handed to the bus (publishing happens only in time triggers).
    receive_flush_period_s: float = Field(0.02, gt=0.0)
    plausibility: PlausibilityLimits = PlausibilityLimits()
    security: SecurityConfig = SecurityConfig()

    @model_validator(mode="after")
    def _profile_defaults(self) -> "V2xConfig":
        defaults = PROFILE_DEFAULTS[self.profile]
        for name in ("gn_version", "its_protocol_version", "cam_mode"):
            if name not in self.model_fields_set:
                setattr(self, name, getattr(defaults, name))
        if "expected_rate_hz" not in self.model_fields_set and self.cam_mode is CamMode.GCDC:
            self.expected_rate_hz = GCDC_RATE_HZ
        return self

    @field_validator("gn_version")
    @classmethod
    def _known_gn_version(cls, value: int) -> int:
        if value not in SUPPORTED_GN_VERSIONS:
            raise ValueError(f"gn_version {value}: supported {SUPPORTED_GN_VERSIONS}")
        return value

    @field_validator("station_type", mode="before")
    @classmethod
    def _station_type_code(cls, value: int | str) -> int:
        if isinstance(value, str) and not value.isdigit():
            try:
                return its_pb2.StationType.Value("STATION_TYPE_" + value.upper())
            except ValueError:
                raise ValueError(f"unknown station type {value!r}") from None
        if int(value) not in its_pb2.StationType.values():
            raise ValueError(f"unknown station type code {value}")
        return int(value)

    @field_validator("clock_epoch_utc")
    @classmethod
    def _aware_epoch(cls, value: datetime | None) -> datetime | None:
        if value is not None and value.tzinfo is None:
            raise ValueError("clock_epoch_utc needs a time zone, e.g. 2016-05-28T10:00:00Z")
        return value

    @field_validator("vehicle_mac")
    @classmethod
    def _six_byte_mac(cls, value: str) -> str:
        parse_mac(value)
        return value

    @property
    def mac_bytes(self) -> bytes:
        return parse_mac(self.vehicle_mac)

    @property
    def clock_epoch_unix_s(self) -> float:
        return 0.0 if self.clock_epoch_utc is None else self.clock_epoch_utc.timestamp()


def parse_mac(text: str) -> bytes:
    """'02:00:00:00:00:01' (or with '-', or bare hex) as 6 bytes; ValueError naming the text otherwise."""
    digits = text.replace(":", "").replace("-", "")
    try:
        mac = bytes.fromhex(digits)
    except ValueError:
        raise ValueError(f"MAC address {text!r} is not hexadecimal") from None
    if len(mac) != MAC_SIZE_BYTES:
        raise ValueError(f"MAC address {text!r} is not {MAC_SIZE_BYTES} bytes")
    return mac
