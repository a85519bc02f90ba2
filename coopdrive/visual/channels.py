"""VisualChannels: the channels Foxglove draws, derived from the stack's messages, defined once for recordings
(McapRecorder) and the live bridge (`coopdrive foxglove`).

Fed every bus message with its key and time; for each it calls emit(topic, foxglove message, time_ns) zero or
more times. The channels (topic: Foxglove schema, from):

- foxglove/<vehicle>/ego: foxglove.LocationFix, one per ego estimate (ego/state)
- foxglove/<vehicle>/gnss: foxglove.LocationFix, one per raw receiver fix: each epoch of the receiver's NMEA bytes
  (gnss/nmea, decoded as geolocation decodes them), or the simulator's fix where it sends no NMEA (gnss/fix)
- foxglove/<vehicle>/v2x_stations: foxglove.LocationFix, one per CAM heard (v2x/cam), frame "station <id>"
- foxglove/transforms: foxglove.FrameTransforms, map -> <vehicle> at each ego estimate
- foxglove/<vehicle>/scene: foxglove.SceneUpdate, one per scene: objects, the MIO, the ego, its planned path
- foxglove/ground_truth: foxglove.SceneUpdate, one per simulator ground truth (namespace "truth/")
- foxglove/map: foxglove.SceneUpdate, the lane map's centre lines, at the start of every MAP_PERIOD_S of time that
  has messages to draw
- foxglove/<vehicle>/signals: foxglove.GeoJSON, the intersections the vehicle heard of (v2x/mapem), their signalised
  movements coloured by the newest SPaT (v2x/spatem), one per MAPEM or SPATEM heard (signal_lanes.py)

What a message draws depends only on the messages, never on the order they arrived in: messages are held until
one sent reorder_s later has arrived (or flush()), then drawn in time order and, within a step, in the order the
pipeline handles them (runtime.pipeline.step_order). A scene is therefore drawn with the ego estimate its scene
service was handed in that step and the plan of the step before, as the car saw them, in a recording and in any
replay of it alike (a run's recording is written a step or two out of time order: its processes' spools interleave).
"""

from __future__ import annotations

import heapq
import itertools
import json
import math
from typing import Callable

from foxglove_schemas_protobuf.FrameTransform_pb2 import FrameTransform
from foxglove_schemas_protobuf.FrameTransforms_pb2 import FrameTransforms
from foxglove_schemas_protobuf.LocationFix_pb2 import LocationFix
from foxglove_schemas_protobuf.Vector3_pb2 import Vector3
from google.protobuf.message import Message

from coopdrive.bus.keys import KeyLayout
from coopdrive.roadmap import RoadMap
from coopdrive.gnss.nmea_decoder import NmeaDecoder
from coopdrive.runtime.pipeline import step_order
from coopdrive.visual.primitives import MAP_FRAME, NANOSECONDS, color, timestamp, yaw_quaternion
from coopdrive.visual.scene_entities import lanes_update, scene_update, truth_update
from coopdrive.visual.signal_lanes import SignalLanes
from coopdrive.v1 import ego_pb2, gnss_pb2, infrastructure_pb2, its_pb2, planner_pb2, scene_pb2, sim_pb2

Emit = Callable[[str, Message, int], None]

TRANSFORMS_TOPIC = "foxglove/transforms"
GROUND_TRUTH_TOPIC = "foxglove/ground_truth"
MAP_TOPIC = "foxglove/map"
# The lane map again now and then, so a viewer that joins late (or seeks in a recording) has it.
MAP_PERIOD_S = 1.0
# How far out of time order a recording's messages may come (a run's: two steps) and still be drawn in order.
RECORDING_REORDER_S = 1.0
EGO_FIX_COLOR = color(0.2, 0.45, 1.0, 1.0)
GNSS_FIX_COLOR = color(1.0, 0.85, 0.1, 1.0)
STATION_FIX_COLOR = color(0.9, 0.2, 0.9, 1.0)
# Row-major ENU 3 x 3 covariance indices of LocationFix.position_covariance.
EAST_EAST, EAST_NORTH, NORTH_EAST, NORTH_NORTH, UP_UP = 0, 1, 3, 4, 8
# EgoState.covariance: row-major 6 x 6 of [x_m, y_m, ...].
EGO_STATE_SIZE = 6


def vehicle_topic(vehicle_id: str, name: str) -> str:
    return f"foxglove/{vehicle_id}/{name}"


class VisualChannels:
    def __init__(self, emit: Emit, road_map: RoadMap | None = None, layout: KeyLayout | None = None,
                 reorder_s: float = 0.0):
        """reorder_s: how long a message is held for older ones to arrive (0: until a newer one does)."""
        self.emit = emit
        self.road_map = road_map
        self.layout = layout or KeyLayout()
        self._ego: dict[str, ego_pb2.EgoState] = {}
        self._behaviour: dict[str, planner_pb2.BehaviourRequest] = {}
        self._map_period: int | None = None
        # Messages not drawn yet, a heap of (time and step order, arrival, vehicle, topic, message, time_ns).
        self._held: list[tuple] = []
        self._arrivals = itertools.count()
        self._newest_ns = 0
        self._reorder_ns = round(reorder_s * NANOSECONDS)
        self._nmea: dict[str, NmeaDecoder] = {}
        # The log time of the NMEA chunk being decoded, for the fixes it completes.
        self._nmea_time_ns = 0
        self._handlers: dict[str, Callable[[str, Message, int], None]] = {
            "ego/state": self._on_ego, "gnss/nmea": self._on_nmea, "gnss/fix": self._on_gnss, "v2x/cam": self._on_cam,
            "scene": self._on_scene, "planner/behaviour": self._on_behaviour, "ground_truth": self._on_truth,
            "v2x/mapem": self._on_mapem, "v2x/spatem": self._on_spatem,
        }
        self._signal_lanes: dict[str, SignalLanes] = {}
        self._draws_key: dict[str, bool] = {}

    def draws(self, key: str) -> bool:
        """Whether on_message makes anything of the messages on this key: a recorder asks for every message it
        writes and hands on only those, so it is answered once per key."""
        known = self._draws_key.get(key)
        if known is None:
            parsed = self.layout.parse(key)
            known = self._draws_key[key] = parsed is not None and parsed[1] in self._handlers
        return known

    def on_message(self, key: str, message: Message, time_ns: int) -> None:
        parsed = self.layout.parse(key)
        if parsed is None or parsed[1] not in self._handlers:
            return
        vehicle_id, topic = parsed
        # A step's time in whole nanoseconds, as recordings stamp it: services sum their step lengths each
        # their own way, so the same step's sent times may differ in their last bit.
        sent_ns = round(message.header.sent_time_s * NANOSECONDS)
        order = (sent_ns, *step_order(message.header, topic, vehicle_id))
        heapq.heappush(self._held, (order, next(self._arrivals), vehicle_id, topic, message, time_ns))
        self._newest_ns = max(self._newest_ns, sent_ns)
        while self._held and self._held[0][0][0] < self._newest_ns - self._reorder_ns:
            self._draw(heapq.heappop(self._held))

    def flush(self) -> None:
        """Draws every message held (a recording's last steps)."""
        while self._held:
            self._draw(heapq.heappop(self._held))

    def _draw(self, held: tuple) -> None:
        _, _, vehicle_id, topic, message, time_ns = held
        self._send_map(time_ns)
        self._handlers[topic](vehicle_id, message, time_ns)

    def _send_map(self, time_ns: int) -> None:
        """At the start of each period with something drawn in it: the same instants whichever messages a file
        holds (a replay's file holds fewer than the run's)."""
        if self.road_map is None or not self.road_map.lanes:
            return
        period_ns = round(MAP_PERIOD_S * NANOSECONDS)
        period = time_ns // period_ns
        if period == self._map_period:
            return
        self._map_period = period
        start_ns = period * period_ns
        self.emit(MAP_TOPIC, lanes_update(self.road_map, start_ns / NANOSECONDS), start_ns)

    def _on_ego(self, vehicle_id: str, ego: ego_pb2.EgoState, time_ns: int) -> None:
        self._ego[vehicle_id] = ego
        time_s = ego.header.sample_time_s
        if ego.latitude_deg or ego.longitude_deg:
            fix = LocationFix(timestamp=timestamp(time_s), frame_id=vehicle_id, latitude=ego.latitude_deg,
                              longitude=ego.longitude_deg, heading=_compass_deg(ego.heading_rad),
                              color=EGO_FIX_COLOR)
            _ego_covariance(fix, ego)
            self.emit(vehicle_topic(vehicle_id, "ego"), fix, time_ns)
        transform = FrameTransform(timestamp=timestamp(time_s), parent_frame_id=MAP_FRAME, child_frame_id=vehicle_id,
                                   translation=Vector3(x=ego.x_m, y=ego.y_m, z=0.0),
                                   rotation=yaw_quaternion(ego.heading_rad))
        self.emit(TRANSFORMS_TOPIC, FrameTransforms(transforms=[transform]), time_ns)

    def _on_gnss(self, vehicle_id: str, fix: gnss_pb2.GnssFix, time_ns: int) -> None:
        out = LocationFix(timestamp=timestamp(fix.header.sample_time_s), frame_id=f"{vehicle_id} gnss",
                          latitude=fix.latitude_deg, longitude=fix.longitude_deg, altitude=fix.altitude_m,
                          color=GNSS_FIX_COLOR)
        if fix.std_east_m or fix.std_north_m:
            covariance = [0.0] * 9
            covariance[EAST_EAST], covariance[NORTH_NORTH] = fix.std_east_m ** 2, fix.std_north_m ** 2
            covariance[UP_UP] = fix.std_up_m ** 2
            out.position_covariance.extend(covariance)
            out.position_covariance_type = LocationFix.DIAGONAL_KNOWN
        if fix.heading_valid:
            out.heading = fix.heading_deg
        self.emit(vehicle_topic(vehicle_id, "gnss"), out, time_ns)

    def _on_nmea(self, vehicle_id: str, chunk: gnss_pb2.NmeaChunk, time_ns: int) -> None:
        decoder = self._nmea.get(vehicle_id)
        if decoder is None:
            decoder = NmeaDecoder(lambda fix: self._on_gnss(vehicle_id, fix, self._nmea_time_ns))
            self._nmea[vehicle_id] = decoder
        self._nmea_time_ns = time_ns
        decoder.feed(chunk.data, chunk.header.sample_time_s)

    def _on_cam(self, vehicle_id: str, cam: its_pb2.CamContent, time_ns: int) -> None:
        position = cam.reference_position
        if not (position.HasField("latitude_deg") and position.HasField("longitude_deg")):
            return  # the CAM's position was "unavailable"
        self.emit(vehicle_topic(vehicle_id, "v2x_stations"),
                  LocationFix(timestamp=timestamp(cam.header.sample_time_s), frame_id=f"station {cam.station_id}",
                              latitude=position.latitude_deg, longitude=position.longitude_deg,
                              color=STATION_FIX_COLOR), time_ns)

    def _on_mapem(self, vehicle_id: str, mapem: infrastructure_pb2.MapemContent, time_ns: int) -> None:
        self._signal_lanes.setdefault(vehicle_id, SignalLanes()).on_mapem(mapem)
        self._send_signal_lanes(vehicle_id, time_ns)

    def _on_spatem(self, vehicle_id: str, spatem: infrastructure_pb2.SpatemContent, time_ns: int) -> None:
        self._signal_lanes.setdefault(vehicle_id, SignalLanes()).on_spatem(spatem, time_ns / NANOSECONDS)
        self._send_signal_lanes(vehicle_id, time_ns)

    def _send_signal_lanes(self, vehicle_id: str, time_ns: int) -> None:
        drawn = self._signal_lanes[vehicle_id].geojson(time_ns / NANOSECONDS)
        if drawn is not None:
            self.emit(vehicle_topic(vehicle_id, "signals"), drawn, time_ns)

    def _on_behaviour(self, vehicle_id: str, behaviour: planner_pb2.BehaviourRequest, time_ns: int) -> None:
        self._behaviour[vehicle_id] = behaviour

    def _on_scene(self, vehicle_id: str, scene: scene_pb2.Scene, time_ns: int) -> None:
        update = scene_update(vehicle_id, scene, self._ego.get(vehicle_id), self._behaviour.get(vehicle_id),
                              self.road_map)
        self.emit(vehicle_topic(vehicle_id, "scene"), update, time_ns)

    def _on_truth(self, vehicle_id: str, truth: sim_pb2.GroundTruth, time_ns: int) -> None:
        self.emit(GROUND_TRUTH_TOPIC, truth_update(truth), time_ns)


def _compass_deg(heading_rad: float) -> float:
    """ENU heading (0 east, counter-clockwise) as LocationFix wants it: degrees clockwise from north."""
    return (90.0 - math.degrees(heading_rad)) % 360.0


def _ego_covariance(fix: LocationFix, ego: ego_pb2.EgoState) -> None:
    if len(ego.covariance) < EGO_STATE_SIZE * EGO_STATE_SIZE:
        return
    covariance = [0.0] * 9
    covariance[EAST_EAST] = ego.covariance[0]
    covariance[EAST_NORTH] = covariance[NORTH_EAST] = ego.covariance[1]
    covariance[NORTH_NORTH] = ego.covariance[EGO_STATE_SIZE + 1]
    fix.position_covariance.extend(covariance)
    fix.position_covariance_type = LocationFix.KNOWN


def recorded_road_map(configs: dict[str, str]) -> RoadMap | None:
    """The lane map the recorded stack localised on: the map_name of its geolocation config (a recording's
    "coopdrive.config" metadata, "<vehicle>/<service>" -> JSON); None when it ran without one."""
    for participant, text in sorted(configs.items()):
        if participant.endswith("/geolocation"):
            try:
                map_name = json.loads(text).get("map_name")
            except (ValueError, AttributeError):
                continue
            return RoadMap.load(map_name) if map_name else None
    return None
