"""Read-only questions about one step's inputs: who is where, who was heard, which events are live."""

from __future__ import annotations

import math
from dataclasses import dataclass

from coopdrive.v1 import header_pb2, its_pb2, scene_pb2

from .config import TYPICAL_CAR_LENGTH_M, PlannerLogicConfig
from .inputs import PlannerInputs

# Metres per degree of latitude (spherical Earth); enough for relative positions within a kilometre.
METRES_PER_DEG_LAT = 111_195.0


@dataclass
class Situation:
    now_s: float
    inputs: PlannerInputs
    config: PlannerLogicConfig

    # --- ego
    def ego_lane(self) -> int:
        ego = self.inputs.ego
        if ego is not None and ego.lane.matched:
            return ego.lane.lane_index
        return self.inputs.scene.ego_lane_index if self.inputs.scene is not None else 0

    def ego_speed_mps(self) -> float:
        return self.inputs.ego.speed_mps if self.inputs.ego is not None else 0.0

    def ego_lateral_offset_m(self) -> float:
        return self.inputs.ego.lane.lateral_offset_m if self.inputs.ego is not None else 0.0

    # --- scene
    def objects(self) -> list[scene_pb2.SceneObject]:
        return [o for o in self.inputs.scene.objects if not o.ghost] if self.inputs.scene is not None else []

    def object(self, object_id: int) -> scene_pb2.SceneObject | None:
        return next((o for o in self.objects() if o.object_id == object_id), None)

    @staticmethod
    def station_of(obj: scene_pb2.SceneObject | None) -> int:
        if obj is None or obj.station_id.confidence < 0:
            return 0
        return int(obj.station_id.value)

    @staticmethod
    def lane_of(obj: scene_pb2.SceneObject) -> int | None:
        return int(obj.lane_index.value) if obj.lane_index.confidence >= 0 else None

    @staticmethod
    def length_of_m(obj: scene_pb2.SceneObject) -> float:
        """Its length where the scene knows it, else a typical car's."""
        known = obj.length_m.confidence >= 0 and obj.length_m.value > 0
        return obj.length_m.value if known else TYPICAL_CAR_LENGTH_M

    @classmethod
    def distance_to_body_m(cls, obj: scene_pb2.SceneObject, x_m: float, y_m: float) -> float:
        """From (x_m, y_m) to the nearest point of the object's centre line: its position (the rear bumper's centre)
        and its length ahead along its heading. Where the heading is unknown, to its position."""
        dx, dy = x_m - obj.position.x_m, y_m - obj.position.y_m
        if obj.heading_rad.confidence < 0:
            return math.hypot(dx, dy)
        along_m = dx * math.cos(obj.heading_rad.value) + dy * math.sin(obj.heading_rad.value)
        along_m = min(max(along_m, 0.0), cls.length_of_m(obj))
        return math.hypot(dx - along_m * math.cos(obj.heading_rad.value), dy - along_m * math.sin(obj.heading_rad.value))

    def object_of_station(self, station_id: int) -> scene_pb2.SceneObject | None:
        if station_id == 0:
            return None
        return next((o for o in self.objects() if self.station_of(o) == station_id), None)

    def forward_mio(self) -> scene_pb2.SceneObject | None:
        scene = self.inputs.scene
        if scene is None or not scene.has_forward_mio:
            return None
        return self.object(scene.forward_mio_id)

    def sonar_beside(self, lane_offset: int) -> list[scene_pb2.SceneObject]:
        """What our side sonars feel at our flank towards that lane (the sign of lane_offset; right is negative).
        The scene makes no lane neighbour of a sonar echo, which says that something is there but not where
        along; for a lane change that is the blind spot's answer, and it is the one sensor that sees a car
        level with us when a lost CAM or a track handover leaves it out of the neighbours."""
        return [o for o in self.objects() if header_pb2.SENSOR_SOURCE_SONAR in o.position.sources
                and o.lateral_offset_m * lane_offset > 0]

    def _neighbour(self, lane_offset: int) -> scene_pb2.LaneNeighbours | None:
        if self.inputs.scene is None:
            return None
        return next((n for n in self.inputs.scene.neighbours if n.lane_offset == lane_offset), None)

    def ahead_in_lane(self, lane_offset: int) -> scene_pb2.SceneObject | None:
        n = self._neighbour(lane_offset)
        return self.object(n.ahead_object_id) if n is not None and n.has_ahead else None

    def behind_in_lane(self, lane_offset: int) -> scene_pb2.SceneObject | None:
        n = self._neighbour(lane_offset)
        return self.object(n.behind_object_id) if n is not None and n.has_behind else None

    # --- V2X
    def _age_s(self, receive_time_s: float) -> float:
        return self.now_s - receive_time_s

    def iclcm(self, station_id: int) -> its_pb2.IclcmContent | None:
        """The station's latest iCLCM if it is not older than the partner silence limit."""
        got = self.inputs.iclcms.get(station_id)
        if got is None or self._age_s(got.receive_time_s) > self.config.partner_silent_s:
            return None
        return got.message

    def silent(self, station_id: int, limit_s: float | None = None) -> bool:
        """Neither an iCLCM nor a CAM from the station within the limit (400 ms by default)."""
        limit = self.config.partner_silent_s if limit_s is None else limit_s
        times = [r.receive_time_s for r in (self.inputs.iclcms.get(station_id), self.inputs.cams.get(station_id))
                 if r is not None]
        return not times or self._age_s(max(times)) > limit

    def rsu_start(self) -> bool:
        return any(r.message.has_low_frequency and r.message.HasField("start_platoon")
                   for r in self.inputs.iclcms.values())

    def rsu_end(self) -> bool:
        return any(r.message.end_of_scenario for r in self.inputs.iclcms.values())

    def active_denm(self, cause_code: int) -> its_pb2.DenmContent | None:
        """A live DENM with the cause: not terminated and within its validity since reception."""
        for station in sorted(self.inputs.denms):
            got = self.inputs.denms[station]
            denm = got.message
            if denm.termination != its_pb2.DENM_TERMINATION_NONE:
                continue
            if self._age_s(got.receive_time_s) > denm.validity_duration_s:
                continue
            if denm.HasField("situation") and denm.situation.event_type.cause_code == cause_code:
                return denm
        return None

    def emergency_stations(self) -> list[int]:
        return sorted(s for s, r in self.inputs.cams.items()
                      if r.message.HasField("low_frequency")
                      and r.message.low_frequency.vehicle_role == its_pb2.VEHICLE_ROLE_EMERGENCY)

    def cam_along_m(self, station_id: int) -> float | None:
        """The station's CAM position along the ego heading from the ego, metres (negative behind)."""
        got = self.inputs.cams.get(station_id)
        return None if got is None else self.along_m(got.message.reference_position)

    def along_m(self, pos: its_pb2.ReferencePosition) -> float | None:
        """A V2X position along the ego heading from the ego, metres (negative behind); None if unknown."""
        ego = self.inputs.ego
        if ego is None or not (pos.HasField("latitude_deg") and pos.HasField("longitude_deg")):
            return None
        north_m = (pos.latitude_deg - ego.latitude_deg) * METRES_PER_DEG_LAT
        east_m = (pos.longitude_deg - ego.longitude_deg) * METRES_PER_DEG_LAT * math.cos(
            math.radians(ego.latitude_deg))
        return east_m * math.cos(ego.heading_rad) + north_m * math.sin(ego.heading_rad)
