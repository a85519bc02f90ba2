"""A GNSS receiver: the true antenna position plus a fix-mode dependent error, written as NMEA 0183."""
from __future__ import annotations

import datetime as dt
import math
import zlib
from dataclasses import dataclass
from typing import Callable, Sequence

import numpy as np

from coopdrive.services.sim.gnss_error import GaussMarkovError, GnssEpisodes, jump_offset_m
from coopdrive.services.sim.nmea_writer import GgaQuality, NmeaFix, NmeaWriter
from coopdrive.services.sim.sensor_config import FixModeName, GnssConfig
from coopdrive.services.sim.sensor_timing import SENDER, SensorTiming, stamp
from coopdrive.v1 import gnss_pb2, sim_pb2

# Heudiasyc Table 1 (NovAtel APN-051): horizontal accuracy per positioning mode, taken as a 2D RMS error;
# the "< 1.0 m" and "< 2.0 m" bounds are read as 0.5 m and 1.0 m typical.
HORIZONTAL_ACCURACY_M = {
    gnss_pb2.FIX_MODE_RTK_FIXED: 0.01,
    gnss_pb2.FIX_MODE_RTK_FLOAT: 0.5,
    gnss_pb2.FIX_MODE_DGPS: 1.0,
    gnss_pb2.FIX_MODE_SBAS: 3.0,
    gnss_pb2.FIX_MODE_SINGLE: 5.0,
}
# Vertical errors of GNSS are typically one and a half times the horizontal per-axis ones.
VERTICAL_TO_HORIZONTAL_RATIO = 1.5
TYPICAL_HDOP = 0.9
DIFFERENTIAL_AGE_S = 1.0

# The gnss_multipath fault's jumps come from their own generator, so that a fault does not shift the noise.
MULTIPATH_FAULT_SEED = 0x6E55

ToGeodetic = Callable[[float, float, float], tuple[float, float, float]]


def axis_sigma_m(fix_mode: int) -> float:
    """One-sigma error per horizontal axis so that the 2D RMS equals the table's accuracy."""
    return HORIZONTAL_ACCURACY_M.get(fix_mode, 0.0) / math.sqrt(2.0)


def fix_message(fix: NmeaFix) -> gnss_pb2.GnssFix:
    """The GnssFix of one solution (header left to the caller)."""
    valid = fix.fix_mode != gnss_pb2.FIX_MODE_NO_FIX
    return gnss_pb2.GnssFix(
        latitude_deg=fix.latitude_deg if valid else 0.0, longitude_deg=fix.longitude_deg if valid else 0.0,
        altitude_m=fix.altitude_m if valid else 0.0, fix_mode=fix.fix_mode, std_east_m=fix.std_east_m,
        std_north_m=fix.std_north_m, std_up_m=fix.std_up_m, speed_mps=fix.speed_mps, course_deg=fix.course_deg,
        satellites=fix.satellites, hdop=fix.hdop)


@dataclass(frozen=True)
class GnssOutput:
    sample_time_s: float
    delivery_time_s: float
    fix: NmeaFix
    sentences: list[bytes]
    # The reported antenna position in the local ENU frame, for the judge (not sent to the stack).
    measured_x_m: float
    measured_y_m: float

    # The same solution as the stack's geolocation decodes it from the sentences (topic gnss/fix).
    message: gnss_pb2.GnssFix

    @property
    def data(self) -> bytes:
        return b"".join(self.sentences)


class GnssSensor:
    def __init__(self, config: GnssConfig, rng: np.random.Generator, to_geodetic: ToGeodetic,
                 utc_epoch: dt.datetime, vehicle_id: str = "") -> None:
        self.config = config
        self.rng = rng
        self.to_geodetic = to_geodetic
        self.utc_epoch = utc_epoch
        self.timing: SensorTiming[GnssOutput] = SensorTiming(config.timing, rng)
        self.writer = NmeaWriter(config.talker_id, GgaQuality(config.sbas_gga_quality))
        self.fix_mode = config.fix_mode.proto
        self.outage = False
        self.offset_east_m, self.offset_north_m = 0.0, 0.0
        self._error = GaussMarkovError(rng, config.error_correlation_time_s)
        self.episodes = GnssEpisodes(config, rng)
        self._near_obstacle = False
        self._fault_multipath: tuple[float, float] | None = None
        self._fault_offset_m = (0.0, 0.0)
        self._fault_next_hop_s = 0.0
        self._fault_rng = np.random.default_rng([MULTIPATH_FAULT_SEED, zlib.crc32(vehicle_id.encode())])
        self.vehicle_id = vehicle_id
        self._sequence = 0

    def set_fix_mode(self, fix_mode: FixModeName | int) -> None:
        """Fault hook (fix_downgrade): the receiver reports this mode and its accuracy from now on."""
        self.fix_mode = fix_mode.proto if isinstance(fix_mode, FixModeName) else int(fix_mode)

    def set_dropout(self, active: bool) -> None:
        """Fault hook (sensor_dropout): the receiver sends nothing at all."""
        self.timing.forced_dropout = active

    def set_outage(self, active: bool) -> None:
        """Fault hook (gnss_outage): the receiver keeps talking but reports no fix."""
        self.outage = active

    def set_offset(self, east_m: float, north_m: float) -> None:
        """Fault hook (gnss_jump): the fixes are off by this much (multipath) until set back to zero."""
        self.offset_east_m, self.offset_north_m = east_m, north_m

    def set_multipath(self, jump_m: float | None, hop_s: float = 1.0) -> None:
        """Fault hook (gnss_multipath): the fixes jump by about jump_m in a new direction every hop_s, the
        receiver still claiming its mode; None ends it."""
        if jump_m is None:
            self._fault_multipath, self._fault_offset_m = None, (0.0, 0.0)
        elif self._fault_multipath != (jump_m, hop_s):
            self._fault_multipath, self._fault_next_hop_s = (jump_m, hop_s), -math.inf

    @property
    def effective_fix_mode(self) -> int:
        if self.outage or self.episodes.outage:
            return gnss_pb2.FIX_MODE_NO_FIX
        return self.episodes.mode(self.fix_mode)

    def poll(self, now_s: float, ego: sim_pb2.VehicleTruth,
             obstacles: Sequence[tuple[sim_pb2.VehicleTruth, float]] = ()) -> list[GnssOutput]:
        """obstacles: the other vehicles with their heights; one taller than the antenna within the configured
        range makes multipath and outages likelier."""
        cfg = self.config
        self._near_obstacle = any(
            height_m > cfg.antenna_height_m and math.hypot(o.x_m - ego.x_m, o.y_m - ego.y_m) < cfg.obstacle_range_m
            for o, height_m in obstacles)
        outputs = []
        for sample_s, delivery_s, (fix, sentences, x_m, y_m) in self.timing.poll(
                now_s, lambda sample_s: self._measure(sample_s, ego)):
            self._sequence += 1
            message = fix_message(fix)
            stamp(message.header, sample_s, delivery_s, self.vehicle_id, SENDER, self._sequence)
            outputs.append(GnssOutput(sample_s, delivery_s, fix, sentences, x_m, y_m, message))
        return outputs

    def _multipath_offset_m(self, sample_s: float) -> tuple[float, float]:
        if self._fault_multipath is not None:
            jump_m, hop_s = self._fault_multipath
            if sample_s >= self._fault_next_hop_s:
                self._fault_offset_m = jump_offset_m(self._fault_rng, jump_m)
                self._fault_next_hop_s = sample_s + hop_s
        east_m, north_m = self.episodes.offset_m
        return (self.offset_east_m + east_m + self._fault_offset_m[0],
                self.offset_north_m + north_m + self._fault_offset_m[1])

    def _measure(self, sample_s: float, ego: sim_pb2.VehicleTruth) -> tuple:
        cfg = self.config
        self.episodes.update(sample_s, self._near_obstacle)
        mode = self.effective_fix_mode
        sigma_h = axis_sigma_m(mode) * cfg.accuracy_scale
        sigma = np.array([sigma_h, sigma_h, sigma_h * VERTICAL_TO_HORIZONTAL_RATIO])
        # First-order Gauss-Markov: stationary standard deviation sigma whatever the correlation time.
        error = sigma * self._error.sample(sample_s)
        offset_east_m, offset_north_m = self._multipath_offset_m(sample_s)
        cos_h, sin_h = math.cos(ego.heading_rad), math.sin(ego.heading_rad)
        true_x = ego.x_m + cfg.antenna_x_m * cos_h - cfg.antenna_y_m * sin_h
        true_y = ego.y_m + cfg.antenna_x_m * sin_h + cfg.antenna_y_m * cos_h
        x_m = true_x + error[0] + offset_east_m
        y_m = true_y + error[1] + offset_north_m
        z_m = cfg.antenna_height_m + error[2]
        lat_deg, lon_deg, alt_m = self.to_geodetic(x_m, y_m, z_m)
        speed = max(ego.speed_mps + cfg.speed_sigma_mps * self.rng.standard_normal(), 0.0)
        course_deg = (90.0 - math.degrees(ego.heading_rad) + cfg.course_sigma_deg * self.rng.standard_normal()) % 360.0
        fix = NmeaFix(
            utc=self.utc_epoch + dt.timedelta(seconds=sample_s),
            latitude_deg=lat_deg, longitude_deg=lon_deg, altitude_m=alt_m, fix_mode=mode,
            speed_mps=speed, course_deg=course_deg,
            std_north_m=sigma[1], std_east_m=sigma[0], std_up_m=sigma[2],
            satellites=0 if mode == gnss_pb2.FIX_MODE_NO_FIX else cfg.satellites,
            hdop=99.9 if mode == gnss_pb2.FIX_MODE_NO_FIX else TYPICAL_HDOP,
            differential_age_s=DIFFERENTIAL_AGE_S if mode >= gnss_pb2.FIX_MODE_SBAS else None,
        )
        return fix, self.writer.epoch(fix), x_m, y_m
