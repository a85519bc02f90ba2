"""Faults a scenario injects at given times, one model per kind, told apart by `type`."""
from __future__ import annotations

import enum
import math
from typing import Annotated, Literal, Union

from pydantic import BaseModel, ConfigDict, Field, model_validator

from coopdrive.services.sim.sensor_config import FixModeName


class SensorName(enum.Enum):
    GNSS = "gnss"
    CAN_STATE = "can_state"
    IMU = "imu"
    RADAR = "radar"
    LIDAR = "lidar"
    CAMERA = "camera"
    SONAR = "sonar"


class _Fault(BaseModel):
    model_config = ConfigDict(extra="forbid", frozen=True)

    start_s: float = Field(ge=0)
    # Open-ended when left out.
    end_s: float = math.inf

    @model_validator(mode="after")
    def _ends_after_start(self) -> _Fault:
        if self.end_s <= self.start_s:
            raise ValueError(f"end_s {self.end_s} must be after start_s {self.start_s}")
        return self

    def active(self, now_s: float) -> bool:
        return self.start_s <= now_s < self.end_s


class GnssOutage(_Fault):
    type: Literal["gnss_outage"]
    vehicle_id: str


class FixDowngrade(_Fault):
    type: Literal["fix_downgrade"]
    vehicle_id: str
    fix_mode: FixModeName


class V2vLoss(_Fault):
    """Packets to and from vehicle_id (every vehicle when left out) are lost with this probability."""

    type: Literal["v2v_loss"]
    vehicle_id: str | None = None
    loss_probability: float = Field(default=1.0, ge=0, le=1)


class V2vCorruption(_Fault):
    type: Literal["v2v_corruption"]
    corruption_probability: float = Field(default=0.1, ge=0, le=1)


class SensorDropout(_Fault):
    type: Literal["sensor_dropout"]
    vehicle_id: str
    sensor: SensorName


class CanErrorBurst(_Fault):
    """The vehicle bus carries error frames at this rate and loses the state frames meanwhile."""

    type: Literal["can_error_burst"]
    vehicle_id: str
    error_frames_per_s: float = Field(default=500.0, gt=0)


class PartnerSilent(_Fault):
    """The vehicle stops transmitting on the radio (it still drives)."""

    type: Literal["partner_silent"]
    vehicle_id: str


class ServiceCrash(_Fault):
    """The named stack service of the vehicle is killed at start_s and restarted at end_s (if given)."""

    type: Literal["service_crash"]
    vehicle_id: str
    service: str = Field(min_length=1)


Fault = Annotated[Union[GnssOutage, FixDowngrade, V2vLoss, V2vCorruption, SensorDropout, CanErrorBurst,
                        PartnerSilent, ServiceCrash], Field(discriminator="type")]
