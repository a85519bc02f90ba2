"""What the planner would have advised at the desk: `coopdrive v2x advise CAPTURE`, a capture with only V2X input.

Every SPATEM of the capture is one step. With an ego pose (latitude, longitude, heading, speed) the real Planner
runs on the capture's MAPEMs and SPATEMs and reports its traffic lights' state and request; with a signal group and a
distance to its stop line instead (a capture without a MAPEM) the SPaT and the advice alone are reported.

The capture's clock need not be the roadside unit's: the first SPATEM that carries its own time stamp (minute of the
year, DSecond) sets the offset from capture time to UTC, so TimeMarks read as the unit meant them.
"""

from __future__ import annotations

from collections.abc import Iterator
from dataclasses import dataclass
from datetime import datetime, timezone
from pathlib import Path

from coopdrive.recording.capture import read_gn_packets
from coopdrive.v1 import ego_pb2, planner_pb2
from coopdrive.v1 import infrastructure_pb2 as pb
from coopdrive.v2x.dsrc_time import unix_s_of_minute_of_year
from coopdrive.v2x.infrastructure import InfrastructureMessage
from coopdrive.v2x.packet import decode_packet
from coopdrive.v2x.reasons import V2xDecodeError
from coopdrive.v2x.timebase import ItsClock

from .config import Intention, PlannerLogicConfig
from .inputs import PlannerInputs, Received
from .planner import Planner
from .signals.advice import Approach, advise
from .signals.phases import Light
from .signals.spat_tracker import SpatTracker

DESK_STATION_ID = 1


@dataclass(frozen=True)
class EgoPose:
    latitude_deg: float
    longitude_deg: float
    heading_rad: float
    speed_mps: float
    intention: Intention = Intention.STRAIGHT


@dataclass(frozen=True)
class GroupApproach:
    """No MAP: the intersection id, the signal group and the distance from the front bumper to its stop line."""

    intersection_id: int
    signal_group: int
    to_stop_line_m: float
    speed_mps: float


def utc_offset_s(content: pb.SpatemContent, capture_s: float) -> float | None:
    """UTC less capture time, from a SPATEM's own time stamp (in the capture's year); None without one."""
    stamped = next((i for i in content.intersections if i.HasField("minute_of_year")
                    and i.HasField("second_of_minute_s")), None)
    if stamped is None:
        return None
    year = datetime.fromtimestamp(capture_s, timezone.utc).year
    return unix_s_of_minute_of_year(year, stamped.minute_of_year, stamped.second_of_minute_s) - capture_s


def _messages(path: Path) -> Iterator[tuple[float, InfrastructureMessage, object]]:
    for frame in read_gn_packets(path):
        try:
            decoded = decode_packet(frame.gn_packet)
        except V2xDecodeError:
            continue
        if decoded.message_type in (InfrastructureMessage.MAPEM, InfrastructureMessage.SPATEM):
            yield frame.time_s, decoded.message_type, decoded.content


def advise_capture(path: Path, ego: EgoPose | GroupApproach, limit_mps: float, glosa: bool,
                   config: PlannerLogicConfig | None = None) -> Iterator[dict]:
    """One record per SPATEM: the step's time (capture clock), the UTC offset used, and what was advised."""
    config = config or PlannerLogicConfig()
    desk = _Desk(ego, limit_mps, glosa, config)
    for capture_s, kind, content in _messages(path):
        if kind is InfrastructureMessage.MAPEM:
            desk.inputs.mapems[content.station_id] = Received(content, capture_s)
            continue
        desk.set_clock(utc_offset_s(content, capture_s))
        desk.inputs.spatems[content.station_id] = Received(content, capture_s)
        yield desk.step(capture_s, content)


class _Desk:
    def __init__(self, ego: EgoPose | GroupApproach, limit_mps: float, glosa: bool, config: PlannerLogicConfig):
        self.ego, self.limit_mps, self.glosa = ego, limit_mps, glosa
        intention = ego.intention if isinstance(ego, EgoPose) else config.signals.intention
        self.config = config.model_copy(update={"cruise_speed_mps": limit_mps, "signals": config.signals.model_copy(
            update={"intention": intention})})
        self.inputs = PlannerInputs(station_id=DESK_STATION_ID, scenario=planner_pb2.SCENARIO_FOLLOW)
        self.clock: ItsClock | None = None
        self.planner: Planner | None = None
        self.tracker: SpatTracker | None = None

    def set_clock(self, offset_s: float | None) -> None:
        """Once, at the first SPATEM: its time stamp's offset, else none (the capture's clock is UTC)."""
        if self.clock is None:
            self.clock = ItsClock(offset_s or 0.0)
            self.planner = Planner(self.config, glosa=self.glosa, clock=self.clock)
            self.tracker = SpatTracker(self.clock, self.config.signals.timing_tolerance_s)

    def step(self, now_s: float, content: pb.SpatemContent) -> dict:
        record = {"time_s": now_s, "utc_offset_s": self.clock.epoch_unix_s}
        if isinstance(self.ego, EgoPose):
            return record | self._planned(now_s)
        return record | self._advised(now_s, content)

    def _planned(self, now_s: float) -> dict:
        pose = self.ego
        ego = ego_pb2.EgoState(latitude_deg=pose.latitude_deg, longitude_deg=pose.longitude_deg,
                               heading_rad=pose.heading_rad, speed_mps=pose.speed_mps)
        self.inputs.ego = ego
        request, _ = self.planner.step(now_s, self.inputs)
        lights = self.planner.lights
        timing = lights.view.timing
        return {"state": self.planner.lights_machine.state.name, "status": lights.view.status.name,
                "why": lights.view.why, **_phase(timing.current if timing else None, now_s),
                "speed_mps": request.desired_speed_mps,
                "stop_line_m": request.stop_line_distance_m if request.has_stop_line else None}

    def _advised(self, now_s: float, content: pb.SpatemContent) -> dict:
        target = self.ego
        self.tracker.on_spatem(content, now_s)
        key = self.tracker.find((0, target.intersection_id), target.signal_group)
        if key is None:
            return {"status": "NO_SPAT", "why": f"no SPaT of intersection {target.intersection_id} "
                                                f"signal group {target.signal_group}"}
        timing = self.tracker.latest[key]
        approach = Approach(now_s, target.to_stop_line_m, target.speed_mps, self.limit_mps)
        advised = advise(timing, approach, self.config.signals, self.glosa)
        why = self.tracker.contradictions.get(key)
        return {"status": "CONTRADICTED" if why else "OK", "why": why.why if why else "",
                **_phase(timing.current, now_s), "advice": advised.advice.name, "speed_mps": advised.speed_mps}


def _phase(current, now_s: float) -> dict:
    if current is None:
        return {"light": Light.UNKNOWN.name, "ends_in_s": None}
    ends_in_s = None if current.end_s is None else current.end_s - now_s
    return {"light": current.light.name, "phase": pb.MovementPhaseState.Name(current.state), "ends_in_s": ends_in_s}


def format_advice(record: dict) -> str:
    ends = "" if record.get("ends_in_s") is None else f" ends in {record['ends_in_s']:.1f} s"
    what = record.get("state") or record.get("advice") or ""
    stop = "" if record.get("stop_line_m") is None else f", stop line {record['stop_line_m']:.1f} m"
    speed = "" if record.get("speed_mps") is None else f" {record['speed_mps']:.1f} m/s"
    light = record.get("light", "")
    return f"{record['time_s']:.2f} {record['status']} {light}{ends} -> {what}{speed}{stop}  {record['why']}".rstrip()
