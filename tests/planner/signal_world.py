"""A signalised intersection as the v2x service publishes it (MapemContent, SpatemContent) and an ego on its
approach: the reference point at 50 N 5 E; ingress lane 1 comes from the west along y = -1.75 m from x = -310 m to
its stop line 10 m west of the reference point; it connects straight on to lane 2 (signal group 1), left to lane 3
(group 2) and right to lane 4 (group 3). The planner's default clock is unix time, so stack times below an hour are TimeMarks."""

from __future__ import annotations

from coopdrive.geodesy import LocalTangentPlane
from coopdrive.services.planner.inputs import Received
from coopdrive.v1 import ego_pb2
from coopdrive.v1 import infrastructure_pb2 as pb

REFERENCE = (50.0, 5.0)
RSU = 901
INTERSECTION = 12
LANE_Y_M = -1.75
STOP_LINE_X_M = -10.0
STRAIGHT, LEFT, RIGHT = 1, 2, 3
GREEN = pb.MOVEMENT_PHASE_STATE_PROTECTED_MOVEMENT_ALLOWED
AMBER = pb.MOVEMENT_PHASE_STATE_PROTECTED_CLEARANCE
RED = pb.MOVEMENT_PHASE_STATE_STOP_AND_REMAIN
RED_AMBER = pb.MOVEMENT_PHASE_STATE_PRE_MOVEMENT
DARK = pb.MOVEMENT_PHASE_STATE_DARK
PLANE = LocalTangentPlane(*REFERENCE)


def _lane(lane_id: int, offsets: list[tuple[float, float]], ingress: bool) -> pb.Lane:
    lane = pb.Lane(lane_id=lane_id, ingress_path=ingress, egress_path=not ingress, lane_type=pb.LANE_TYPE_VEHICLE)
    for east_m, north_m in offsets:
        lane.nodes.add(east_m=east_m, north_m=north_m)
    return lane


def mapem(lane_shift_m: float = 0.0, intersection_id: int = INTERSECTION, region: int | None = None
          ) -> pb.MapemContent:
    """The intersection; lane_shift_m moves ingress lane 1 north (a MAP that does not match the road)."""
    content = pb.MapemContent(station_id=RSU)
    intersection = content.intersections.add(reference_latitude_deg=REFERENCE[0],
                                             reference_longitude_deg=REFERENCE[1], lane_width_m=3.5)
    intersection.id.id = intersection_id
    if region is not None:
        intersection.id.region = region
    ingress = _lane(1, [(STOP_LINE_X_M, LANE_Y_M + lane_shift_m), (-100.0, 0.0), (-200.0, 0.0)], ingress=True)
    for to_lane, group in ((2, STRAIGHT), (3, LEFT), (4, RIGHT)):
        ingress.connections.add(to_lane_id=to_lane, signal_group=group)
    intersection.lanes.extend([ingress, _lane(2, [(10.0, LANE_Y_M), (100.0, 0.0)], ingress=False),
                               _lane(3, [(1.75, 10.0), (0.0, 100.0)], ingress=False),
                               _lane(4, [(-1.75, -10.0), (0.0, -100.0)], ingress=False)])
    intersection.signal_groups.extend([STRAIGHT, LEFT, RIGHT])
    return content


def event(state: int, min_end_s: float | None = None, likely_s: float | None = None,
          max_end_s: float | None = None) -> pb.MovementEvent:
    e = pb.MovementEvent(state=state)
    for field, value in (("min_end_time_s", min_end_s), ("likely_time_s", likely_s), ("max_end_time_s", max_end_s)):
        if value is not None:
            setattr(e, field, value)
    return e


def spatem(events: list[pb.MovementEvent], group: int = STRAIGHT) -> pb.SpatemContent:
    content = pb.SpatemContent(station_id=RSU)
    intersection = content.intersections.add()
    intersection.id.id = INTERSECTION
    intersection.signal_groups.add(signal_group=group, events=events)
    return content


def light(*phases: tuple[int, float | None]) -> pb.SpatemContent:
    """Group 1 through (state, likely end) phases, the current first; an actuated controller's likelyTime only."""
    return spatem([event(state, likely_s=end_s) for state, end_s in phases])


def ego_at(x_m: float, speed_mps: float = 13.9, y_m: float = LANE_Y_M, heading_rad: float = 0.0
           ) -> ego_pb2.EgoState:
    """The ego's rear axle x_m east and y_m north of the reference point."""
    latitude_deg, longitude_deg, _ = PLANE.to_geodetic(x_m, y_m)
    e = ego_pb2.EgoState(x_m=x_m, y_m=y_m, heading_rad=heading_rad, speed_mps=speed_mps,
                         latitude_deg=latitude_deg, longitude_deg=longitude_deg)
    e.lane.matched = True
    return e


def heard(message, at_s: float) -> dict[int, Received]:
    return {RSU: Received(message, at_s)}


def fixed_time(t: float, green_s: float, amber_s: float, red_s: float, offset_s: float = 0.0
               ) -> tuple[tuple[int, float], ...]:
    """A fixed-time plan for group 1 seen at t: green from offset_s, then amber, then red, repeated; the phase at t
    and the three after it, each with its end."""
    plan = ((GREEN, green_s), (AMBER, amber_s), (RED, red_s))
    cycle_s = green_s + amber_s + red_s
    start_s = offset_s + ((t - offset_s) // cycle_s) * cycle_s
    phases, index = [], 0
    while len(phases) < 4:
        state, length_s = plan[index % 3]
        if start_s + length_s > t:
            phases.append((state, start_s + length_s))
        start_s += length_s
        index += 1
    return tuple(phases)
