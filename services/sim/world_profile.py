"""World profiles: `real` (the configuration defaults: every error source a real device has) and `ideal` (the
kind world the simulator had before: no misses, clutter, bias, burst loss, driving resistance; 1 cm white RTK
noise; fixed latencies; scripted vehicles sending their exact state).

The ideal world is data: for each configuration family, the values it gives every field a scenario (or a
caller) did not set itself. Tests that need exact answers ask for it explicitly (`coopdrive run --world ideal`,
`world: ideal` in a scenario file, or `ideal(config)` on a configuration object).
"""
from __future__ import annotations

import enum
import math
from typing import Any, TypeVar

from pydantic import BaseModel

from coopdrive.services.sim.channel_config import GilbertElliottConfig, RadioChannelConfig
from coopdrive.services.sim.profiles import VehicleProfile
from coopdrive.services.sim.sensor_config import (CameraConfig, CanStateConfig, GnssConfig, ImuConfig, LidarConfig,
                                                  RadarConfig, SensorSuiteConfig, SonarConfig)


class WorldProfile(enum.Enum):
    REAL = "real"
    IDEAL = "ideal"


_FIXED_LATENCY = {"timing": {"latency_jitter_s": 0.0, "dropout_probability": 0.0}}

IDEAL_SENSORS: dict[str, dict[str, Any]] = {
    "gnss": {**_FIXED_LATENCY, "error_correlation_time_s": 0.0, "degradation_rate_per_h": 0.0,
             "multipath_rate_per_h": 0.0, "multipath_near_obstacle_rate_per_h": 0.0},
    "can_state": _FIXED_LATENCY,
    "imu": {**_FIXED_LATENCY, "accel_turn_on_bias_sigma_mps2": 0.0, "yaw_rate_turn_on_bias_sigma_radps": 0.0},
    "radar": {"timing": {**_FIXED_LATENCY["timing"], "rate_hz": 20.0}, "range_sigma_m": 0.25,
              "azimuth_sigma_rad": math.radians(0.3), "range_rate_sigma_mps": 0.12, "range_bias_m": 0.0,
              "azimuth_bias_rad": 0.0, "miss_probability": 0.0, "false_alarms_per_scan": 0.0,
              "track_id_switch_probability": 0.0, "range_resolution_m": 0.0, "azimuth_resolution_rad": 0.0,
              "width_sigma_m": 0.0},
    "lidar": {**_FIXED_LATENCY, "point_dropout_probability": 0.0, "clutter_probability": 0.0},
    "camera": {**_FIXED_LATENCY, "miss_probability": 0.0, "misclassification_probability": 0.0,
               "width_sigma_m": 0.0},
    "sonar": _FIXED_LATENCY,
}
IDEAL_BURST: dict[str, Any] = {"good_to_bad_probability": 0.0, "bad_to_good_probability": 1.0,
                               "loss_in_good_probability": 0.0, "loss_in_bad_probability": 1.0}
IDEAL_CHANNEL: dict[str, Any] = {"distance_scale_m": 40.0, "burst": IDEAL_BURST}
IDEAL_VEHICLE: dict[str, Any] = {"rolling_resistance_mps2": 0.0, "drag_1pm": 0.0}

_IDEAL_BY_TYPE: dict[type, dict[str, Any]] = {
    SensorSuiteConfig: IDEAL_SENSORS, GnssConfig: IDEAL_SENSORS["gnss"], CanStateConfig: IDEAL_SENSORS["can_state"],
    ImuConfig: IDEAL_SENSORS["imu"], RadarConfig: IDEAL_SENSORS["radar"], LidarConfig: IDEAL_SENSORS["lidar"],
    CameraConfig: IDEAL_SENSORS["camera"], SonarConfig: IDEAL_SENSORS["sonar"], RadioChannelConfig: IDEAL_CHANNEL,
    GilbertElliottConfig: IDEAL_BURST, VehicleProfile: IDEAL_VEHICLE,
}

Model = TypeVar("Model", bound=BaseModel)


def overridden(model: Model, overrides: dict[str, Any], forced: bool = False) -> Model:
    """model with the overrides on every field it was not given explicitly; a nested model that was itself left
    to its default takes all of its overrides (`forced`)."""
    update = {}
    for name, value in overrides.items():
        given = name in model.model_fields_set and not forced
        current = getattr(model, name)
        if isinstance(value, dict):
            if current is not None:
                update[name] = overridden(current, value, not given)
        elif not given:
            update[name] = value
    return model.model_copy(update=update)


def ideal(model: Model) -> Model:
    """A sensor, channel or vehicle-profile configuration in the ideal world (what it set itself kept; a vehicle
    profile is a fixed table, so it loses its driving resistance whatever it was built with)."""
    return overridden(model, _IDEAL_BY_TYPE[type(model)], forced=isinstance(model, VehicleProfile))
