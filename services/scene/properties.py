"""The fused properties of one object and which readings support which property.

Position, speed, acceleration and heading take their values from the track filter; the filter is the
confidence-weighted average for them. Width, length, class and station id have no filter and blend
by (C4) in confidence.py.
"""

from __future__ import annotations

from collections.abc import Callable

from coopdrive.v1 import header_pb2, sensors_pb2

from .config import SourceConfig, TrackingConfig
from .confidence import FusedProperty
from .measurement import Measurement

_SPEED_SOURCES = (header_pb2.SENSOR_SOURCE_RADAR, header_pb2.SENSOR_SOURCE_V2V)
_DERIVED_SPEED_SOURCES = (header_pb2.SENSOR_SOURCE_LIDAR, header_pb2.SENSOR_SOURCE_CAMERA)


class ObjectProperties:
    def __init__(self, source_config: Callable[[int], SourceConfig], tracking: TrackingConfig) -> None:
        def make(closer: float = 1.0) -> FusedProperty:
            return FusedProperty(source_config, new_data_bias=tracking.new_data_bias, closer_bias=closer)

        self._derived_quality = tracking.derived_quality
        self.position = make()
        self.speed = make()
        self.accel = make()
        self.heading = make()
        self.length = make()
        # A narrower reading is not safer, so width gets no closer bias; nor does anything but range.
        self.width = make()
        self.object_class = make()
        self.station_id = make()
        # The partner's own reported acceleration, kept as sent (brief: the object carries it).
        self.reported_accel_mps2: float | None = None
        # When the latest V2V reading was measured (0: never).
        self.v2v_time_s = 0.0
        self.object_class_value = sensors_pb2.OBJECT_CLASS_UNSPECIFIED

    def support(self, meas: Measurement, quality: float, v2v_weight: float = 1.0) -> None:
        """Credit every property this reading says something about. v2v_weight scales V2V by trust."""
        q = quality * meas.quality
        if meas.source == header_pb2.SENSOR_SOURCE_V2V:
            q *= v2v_weight
        t = meas.time_s
        self.position.support(meas.source, t, q)
        if meas.source in _SPEED_SOURCES:
            self.speed.support(meas.source, t, q)
        elif meas.source in _DERIVED_SPEED_SOURCES:
            # The filter's velocity out of a series of positions gives the direction as well as the speed.
            self.speed.support(meas.source, t, q * self._derived_quality)
            self.heading.support(meas.source, t, q * self._derived_quality)
        if meas.source == header_pb2.SENSOR_SOURCE_V2V:
            self.heading.support(meas.source, t, q)
            self.accel.support(meas.source, t, q)
            self.reported_accel_mps2 = meas.accel_mps2
            self.v2v_time_s = max(self.v2v_time_s, t)
            if meas.station_id is not None:
                self.station_id.update(meas.source, t, float(meas.station_id), q)
        elif meas.source == header_pb2.SENSOR_SOURCE_RADAR:
            self.heading.support(meas.source, t, q * self._derived_quality)
        if meas.width_m is not None:
            self.width.update(meas.source, t, meas.width_m, q)
        if meas.length_m is not None:
            self.length.update(meas.source, t, meas.length_m, q)
        if meas.object_class != sensors_pb2.OBJECT_CLASS_UNSPECIFIED:
            self.object_class.support(meas.source, t, q)
            self.object_class_value = meas.object_class
        elif meas.source == header_pb2.SENSOR_SOURCE_V2V and self.object_class_value == sensors_pb2.OBJECT_CLASS_UNSPECIFIED:
            # A CAM sender is a vehicle; the camera may refine car versus truck.
            self.object_class.support(meas.source, t, q)
            self.object_class_value = sensors_pb2.OBJECT_CLASS_CAR

    def last_support_s(self) -> float:
        return self.position.last_support_s()
