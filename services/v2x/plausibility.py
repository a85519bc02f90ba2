"""Plausibility of decoded messages: identity, time and kinematics checks against each station's history.

A message that fails is rejected with a PlausibilityReason (its value is a key of V2xStatus.rejected_by_reason,
next to the decoder's RejectReason values). Only accepted messages update the history, so one bad packet
cannot poison the checks of the good ones after it.
"""

from __future__ import annotations

import enum
import math
from dataclasses import dataclass

from coopdrive.services.v2x.config import PlausibilityLimits
from coopdrive.v2x.its_pdu import ItsMessageId
from coopdrive.v2x.packet import MessageType
from coopdrive.v2x.timebase import MS_PER_S
from coopdrive.v2x.units import EARTH_RADIUS_M



class PlausibilityReason(enum.Enum):
    STATION_ID_CHANGED = "station_id_changed"
    TOO_OLD = "too_old"
    FROM_THE_FUTURE = "from_the_future"
    EXPIRED = "expired"
    NOT_NEWER = "not_newer"
    IMPLAUSIBLE_SPEED = "implausible_speed"
    IMPLAUSIBLE_ACCELERATION = "implausible_acceleration"
    POSITION_JUMP = "position_jump"


# Reasons judged against the station's previous message, after which the next message is judged against
# the rejected one.
RELOCATING_REASONS = frozenset({PlausibilityReason.POSITION_JUMP, PlausibilityReason.IMPLAUSIBLE_ACCELERATION})

@dataclass(frozen=True)
class Observation:
    """What the checks need from one decoded message, SI units."""

    source_mac: bytes | None
    station_id: int
    message_type: MessageType
    # Generation time (CAM, iCLCM) or reference time (DENM), TAI ms.
    time_tai_ms: int
    latitude_deg: float | None = None
    longitude_deg: float | None = None
    speed_mps: float | None = None
    accel_mps2: float | None = None
    # DENM only: detection time and validity.
    detection_tai_ms: int | None = None
    validity_s: float | None = None


@dataclass
class _Identity:
    station_id: int
    last_receive_tai_ms: int


def ground_distance_m(lat1_deg: float, lon1_deg: float, lat2_deg: float, lon2_deg: float) -> float:
    """Equirectangular distance: exact enough over the metres between two CAMs."""
    mean_lat_rad = math.radians((lat1_deg + lat2_deg) / 2)
    north_m = math.radians(lat2_deg - lat1_deg) * EARTH_RADIUS_M
    east_m = math.radians(lon2_deg - lon1_deg) * EARTH_RADIUS_M * math.cos(mean_lat_rad)
    return math.hypot(east_m, north_m)


class PlausibilityChecker:
    """Checks each message against the station's previous one; see RELOCATING_REASONS."""
    def __init__(self, limits: PlausibilityLimits, loss_timeout_s: float):
        self.limits = limits
        self.loss_timeout_ms = loss_timeout_s * MS_PER_S
        self._identities: dict[bytes, _Identity] = {}
        self._last: dict[tuple[int, ItsMessageId], Observation] = {}
        # The latest message rejected for a RELOCATING_REASON, per station and type.
        self._relocated: dict[tuple[int, ItsMessageId], Observation] = {}

    def check(self, observation: Observation, receive_tai_ms: int) -> PlausibilityReason | None:
        """None when plausible (and then remembered), else the first reason it is not."""
        reason = (self._identity_reason(observation, receive_tai_ms) or self._time_reason(observation, receive_tai_ms)
                  or self._kinematics_reason(observation, self._last))
        key = (observation.station_id, observation.message_type)
        if reason in RELOCATING_REASONS and key in self._relocated \
                and self._kinematics_reason(observation, self._relocated) is None:
            reason = None
        self._relocated.pop(key, None)
        if reason is None:
            if observation.source_mac:
                self._identities[observation.source_mac] = _Identity(observation.station_id, receive_tai_ms)
            self._last[key] = observation
        elif reason in RELOCATING_REASONS:
            # The next message may also be judged against this one: a station that really is elsewhere (or
            # was wrong before) is followed again after one lost message instead of shut out for good.
            self._relocated[key] = observation
        return reason

    def forget(self, station_id: int) -> None:
        for key in [key for key in self._last if key[0] == station_id]:
            del self._last[key]
        for key in [key for key in self._relocated if key[0] == station_id]:
            del self._relocated[key]
        for mac in [mac for mac, identity in self._identities.items() if identity.station_id == station_id]:
            del self._identities[mac]

    def _identity_reason(self, o: Observation, receive_tai_ms: int) -> PlausibilityReason | None:
        known = self._identities.get(o.source_mac) if o.source_mac else None
        if known is None or known.station_id == o.station_id:
            return None
        # A new pseudonym after a silence is allowed; a different station id mid-stream is not.
        if receive_tai_ms - known.last_receive_tai_ms <= self.loss_timeout_ms:
            return PlausibilityReason.STATION_ID_CHANGED
        return None

    def _time_reason(self, o: Observation, receive_tai_ms: int) -> PlausibilityReason | None:
        lim = self.limits
        if o.message_type == ItsMessageId.DENM:
            # Repetitions keep the reference time of the event: judge the detection time and validity instead.
            detection = o.detection_tai_ms if o.detection_tai_ms is not None else o.time_tai_ms
            if detection - receive_tai_ms > lim.max_future_s * MS_PER_S:
                return PlausibilityReason.FROM_THE_FUTURE
            if o.validity_s is not None and receive_tai_ms > detection + o.validity_s * MS_PER_S:
                return PlausibilityReason.EXPIRED
        else:
            age_ms = receive_tai_ms - o.time_tai_ms
            if age_ms > lim.max_age_s * MS_PER_S:
                return PlausibilityReason.TOO_OLD
            if -age_ms > lim.max_future_s * MS_PER_S:
                return PlausibilityReason.FROM_THE_FUTURE
        previous = self._last.get((o.station_id, o.message_type))
        if previous is not None and o.message_type != ItsMessageId.DENM and o.time_tai_ms <= previous.time_tai_ms:
            return PlausibilityReason.NOT_NEWER
        return None

    def _kinematics_reason(self, o: Observation,
                           previous_of: dict[tuple[int, ItsMessageId], Observation]) -> PlausibilityReason | None:
        lim = self.limits
        if o.speed_mps is not None and o.speed_mps > lim.max_speed_mps:
            return PlausibilityReason.IMPLAUSIBLE_SPEED
        if o.accel_mps2 is not None and abs(o.accel_mps2) > lim.max_accel_mps2:
            return PlausibilityReason.IMPLAUSIBLE_ACCELERATION
        previous = previous_of.get((o.station_id, o.message_type))
        if previous is None or o.message_type != ItsMessageId.CAM:
            return None
        dt_s = (o.time_tai_ms - previous.time_tai_ms) / MS_PER_S
        if None not in (o.speed_mps, previous.speed_mps) and \
                abs(o.speed_mps - previous.speed_mps) > lim.max_accel_mps2 * dt_s + lim.speed_jump_tolerance_mps:
            return PlausibilityReason.IMPLAUSIBLE_ACCELERATION
        if None not in (o.latitude_deg, o.longitude_deg, previous.latitude_deg, previous.longitude_deg):
            jump_m = ground_distance_m(previous.latitude_deg, previous.longitude_deg, o.latitude_deg, o.longitude_deg)
            if jump_m > lim.max_speed_mps * dt_s + lim.position_jump_tolerance_m:
                return PlausibilityReason.POSITION_JUMP
        return None
