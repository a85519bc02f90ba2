"""What each V2V station's controller is asking of its driveline, from its iCLCM, put on its scene object.

The CAM reports the acceleration a vehicle has; the iCLCM's targetLongitudinalAcceleration is the one it
requests, which the vehicle reaches a driveline lag later. A follower that brakes on the request starts as
early as its predecessor (Ploeg et al. feed the predecessor's input forward for the same reason).
"""

from __future__ import annotations

import math
from dataclasses import dataclass

from coopdrive.v1 import header_pb2, its_pb2, scene_pb2


@dataclass(frozen=True)
class _Request:
    accel_mps2: float
    sample_time_s: float


class IntendedAccelerations:
    def __init__(self, max_age_s: float, min_trust: float) -> None:
        """max_age_s: a request older than this says nothing about now (the CACC fallback limit, 400 ms);
        min_trust: a station trusted less than this (its claims disagree with our sensors) is not believed."""
        self.max_age_s = max_age_s
        self.min_trust = min_trust
        self._latest: dict[int, _Request] = {}

    def on_iclcm(self, iclcm: its_pb2.IclcmContent, sample_time_s: float) -> None:
        if not iclcm.HasField("target_longitudinal_acceleration_mps2"):
            return
        accel = iclcm.target_longitudinal_acceleration_mps2
        latest = self._latest.get(iclcm.station_id)
        if math.isfinite(accel) and (latest is None or sample_time_s >= latest.sample_time_s):
            self._latest[iclcm.station_id] = _Request(accel, sample_time_s)

    def annotate(self, scene: scene_pb2.Scene, now_s: float) -> None:
        """Sets intended_accel_mps2 on every object linked to a trusted station whose request is fresh."""
        for obj in scene.objects:
            if obj.station_id.confidence <= 0 or obj.v2v_trust < self.min_trust:
                continue
            request = self._latest.get(obj.station_id.value)
            if request is None or now_s - request.sample_time_s > self.max_age_s:
                continue
            intended = obj.intended_accel_mps2
            intended.value = request.accel_mps2
            intended.confidence = obj.station_id.confidence
            intended.sources.append(header_pb2.SENSOR_SOURCE_V2V)
            intended.valid_until_s = request.sample_time_s + self.max_age_s
