"""The fused properties of one object and which readings support which property.

Position, speed, acceleration and heading take their values from the track filter; the filter is the
confidence-weighted average for them. Width, length, class and station id have no filter and blend
by (C4) in support_table.py. Every object's properties are one row of a SupportTable shared by all objects
(one slot per property), so a frame's readings credit every object in a few array operations (support_many).
"""

from __future__ import annotations

from collections.abc import Callable

import numpy as np

from coopdrive.v1 import header_pb2, sensors_pb2

from .config import SourceConfig, TrackingConfig
from .confidence import FusedProperty
from .measurement import Measurement
from .support_table import ONE_BY_ONE_MAX, SupportTable

_SPEED_SOURCES = (header_pb2.SENSOR_SOURCE_RADAR, header_pb2.SENSOR_SOURCE_V2V)
_DERIVED_SPEED_SOURCES = (header_pb2.SENSOR_SOURCE_LIDAR, header_pb2.SENSOR_SOURCE_CAMERA)
_V2V = header_pb2.SENSOR_SOURCE_V2V
# The table's slot of each property.
SLOTS = ("position", "speed", "accel", "heading", "length", "width", "object_class", "station_id")
POSITION, SPEED, ACCEL, HEADING, LENGTH, WIDTH, OBJECT_CLASS, STATION_ID = range(len(SLOTS))
_VALUE_SLOTS = [WIDTH, LENGTH, STATION_ID]


def property_table(source_config: Callable[[int], SourceConfig], tracking: TrackingConfig) -> SupportTable:
    """A table for the properties of many objects. No slot has a closer bias: a narrower reading is not safer,
    and the filter, not the table, estimates the distance-like values."""
    return SupportTable(source_config, len(SLOTS), new_data_bias=tracking.new_data_bias)


class ObjectProperties:
    def __init__(self, source_config: Callable[[int], SourceConfig], tracking: TrackingConfig,
                 table: SupportTable | None = None) -> None:
        """One object's properties: a row of table (of a table of their own without one)."""
        self.table = table if table is not None else property_table(source_config, tracking)
        self.row = self.table.allocate()
        self.derived_quality = tracking.derived_quality
        self.position, self.speed, self.accel, self.heading, self.length, self.width, self.object_class, \
            self.station_id = (FusedProperty.in_table(self.table, self.row, slot) for slot in range(len(SLOTS)))
        # The partner's own reported acceleration, kept as sent (brief: the object carries it).
        self.reported_accel_mps2: float | None = None
        # When the latest V2V reading was measured (0: never).
        self.v2v_time_s = 0.0
        self.object_class_value = sensors_pb2.OBJECT_CLASS_UNSPECIFIED

    def support(self, meas: Measurement, quality: float, v2v_weight: float = 1.0) -> None:
        """Credit every property this reading says something about. v2v_weight scales V2V by trust. support_many's
        work for one reading, in plain floats (the same IEEE products)."""
        q = quality * meas.quality * (v2v_weight if meas.source == _V2V else 1.0)
        _support_one_by_one(meas.source, [self], [meas], [q])

    def release(self) -> None:
        """Give the row back to the table: the object is gone."""
        self.table.release(self.row)

    def last_support_s(self) -> float:
        return self.position.last_support_s()


def support_many(props: list[ObjectProperties], measurements: list[Measurement], qualities,
                 v2v_weight: float = 1.0) -> None:
    """ObjectProperties.support of reading k for props[k] (all of one table), a few array operations per source."""
    by_source: dict[int, list[int]] = {}
    for k, meas in enumerate(measurements):
        by_source.setdefault(meas.source, []).append(k)
    qualities = np.asarray(qualities, dtype=float)
    for source, ks in by_source.items():
        group = [measurements[k] for k in ks]
        q = qualities[ks] * np.array([m.quality for m in group]) * (v2v_weight if source == _V2V else 1.0)
        _support_source(source, [props[k] for k in ks], group, q)


def _support_source(source: int, props: list[ObjectProperties], group: list[Measurement], q: np.ndarray) -> None:
    if len(group) <= ONE_BY_ONE_MAX:
        _support_one_by_one(source, props, group, q.tolist())
        return
    table = props[0].table
    slots, shares = _slot_shares(source, props[0].derived_quality)
    class_quality = q * np.array([_class_reading(source, prop, meas) for prop, meas in zip(props, group, strict=True)])
    for prop, meas in zip(props, group, strict=True):
        _note_v2v(source, prop, meas)
    rows, t = np.array([p.row for p in props]), np.array([m.time_s for m in group])
    table.support(rows, slots + [OBJECT_CLASS], source, t,
                  np.column_stack((q[:, None] * np.array(shares), class_quality)))
    # Values no filter estimates: NaN where a reading gives none.
    values = np.array([[value for _, value in _values_of(source, m)] for m in group], dtype=float)
    table.update(rows, _VALUE_SLOTS, source, t, values, q)


def _support_one_by_one(source: int, props: list[ObjectProperties], group: list[Measurement],
                        q: list[float]) -> None:
    """_support_source for a few readings, one table entry at a time in plain floats."""
    table = props[0].table
    slots, shares = _slot_shares(source, props[0].derived_quality)
    for prop, meas, q_k in zip(props, group, q, strict=True):
        class_k = q_k * _class_reading(source, prop, meas)
        _note_v2v(source, prop, meas)
        for slot, share in zip(slots, shares, strict=True):
            table.support_one(prop.row, slot, source, meas.time_s, q_k * share)
        table.support_one(prop.row, OBJECT_CLASS, source, meas.time_s, class_k)
        for slot, value in _values_of(source, meas):
            if value is not None:
                table.update_one(prop.row, slot, source, meas.time_s, value, q_k)


def _note_v2v(source: int, prop: ObjectProperties, meas: Measurement) -> None:
    """A V2V reading's own acceleration and time, kept as sent."""
    if source == _V2V:
        prop.reported_accel_mps2 = meas.accel_mps2
        prop.v2v_time_s = max(prop.v2v_time_s, meas.time_s)


def _slot_shares(source: int, derived_quality: float) -> tuple[list[int], list[float]]:
    """The slots every reading of this source supports, and the share of its quality each gets."""
    slots, shares = [POSITION], [1.0]
    if source in _SPEED_SOURCES:
        slots.append(SPEED)
        shares.append(1.0)
    elif source in _DERIVED_SPEED_SOURCES:
        # The filter's velocity out of a series of positions gives the direction as well as the speed.
        slots += [SPEED, HEADING]
        shares += [derived_quality, derived_quality]
    if source == _V2V:
        slots += [HEADING, ACCEL]
        shares += [1.0, 1.0]
    elif source == header_pb2.SENSOR_SOURCE_RADAR:
        slots.append(HEADING)
        shares.append(derived_quality)
    return slots, shares


def _values_of(source: int, meas: Measurement) -> tuple[tuple[int, float | None], ...]:
    """(slot, value or None) of the properties no filter estimates: width, length and a V2V station's id."""
    station = float(meas.station_id) if source == _V2V and meas.station_id is not None else None
    return (WIDTH, meas.width_m), (LENGTH, meas.length_m), (STATION_ID, station)


def _class_reading(source: int, prop: ObjectProperties, meas: Measurement) -> float:
    """1 where the reading says what class the object is (and sets it), 0 elsewhere."""
    if meas.object_class != sensors_pb2.OBJECT_CLASS_UNSPECIFIED:
        prop.object_class_value = meas.object_class
        return 1.0
    if source == _V2V and prop.object_class_value == sensors_pb2.OBJECT_CLASS_UNSPECIFIED:
        # A CAM sender is a vehicle; the camera may refine car versus truck.
        prop.object_class_value = sensors_pb2.OBJECT_CLASS_CAR
        return 1.0
    return 0.0
