"""EgoLaneFusion: the ego lane from the road map (at the estimated position) and the camera's lane markings.

The two see the lane differently. The map gives the lane index, width and curvature exactly, but its offset and
heading error are only as good as the position estimate: a GNSS error moves the car in the map, not on the road.
The camera measures offset and heading error relative to the painted lines, whatever GNSS says, but knows no
lane index. So:

- the camera's lane is counted from the map's where the two first agree, and then by the lines the camera sees
  the car cross (its offset jumps by about a lane width);
- map and camera, both expressed in the camera's lane, are compared: within `gate_sigma` standard deviations of
  their difference they are fused by inverse-variance weighting (the minimum-variance combination of two
  independent measurements); beyond it the map-and-GNSS offset is wrong and the camera alone is used.

In the vehicle frame (rear axle, x forward, y left) a lane's centre line is y = -offset - tan(heading error) x +
(curvature / 2) x^2 + ..., so a camera marking pair gives offset = -(c0_left + c0_right) / 2, heading error =
-atan((c1_left + c1_right) / 2) and curvature = c2_left + c2_right. Nothing here reads a clock.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

from coopdrive.roadmap.lane import lateral_offset_after_m
from coopdrive.v1 import ego_pb2, scene_pb2, sensors_pb2

from .config import LaneFusionConfig
from .frontends import LaneMarkings

HEADING = 2
STATE_SIZE = 6


@dataclass(frozen=True)
class LaneView:
    """One source's view of the ego lane: offset from the centre (positive left), heading error, their stds."""

    lateral_offset_m: float
    offset_std_m: float
    heading_error_rad: float
    heading_std_rad: float
    lane_width_m: float
    curvature_1pm: float


def map_view(ego: ego_pb2.EgoState, config: LaneFusionConfig, time_s: float) -> LaneView | None:
    """The map's lane through the ego estimate, moved on to time_s; its offset is as uncertain as the position."""
    lane = ego.lane
    if not lane.matched:
        return None
    heading_var = ego.covariance[HEADING * STATE_SIZE + HEADING] if len(ego.covariance) == STATE_SIZE ** 2 else 0.0
    age_s = max(0.0, time_s - ego.header.sample_time_s)
    offset_m = lateral_offset_after_m(lane.lateral_offset_m, ego.speed_mps, lane.heading_error_rad, age_s)
    return LaneView(offset_m, math.hypot(ego.position_std_m, config.map_offset_std_m),
                    lane.heading_error_rad, math.sqrt(max(heading_var, 0.0) + config.map_heading_std_rad ** 2),
                    lane.lane_width_m, lane.curvature_1pm)


def camera_view(markings: LaneMarkings, config: LaneFusionConfig, fallback_width_m: float | None,
                speed_mps: float, time_s: float) -> LaneView | None:
    """The camera's lane from its usable markings, moved on to time_s along the heading error."""
    usable = {m.side: m for m in markings.markings if m.quality >= config.min_marking_quality
              and all(math.isfinite(v) for v in (m.c0_m, m.c1, m.c2_1pm))}
    left, right = usable.get(sensors_pb2.LANE_SIDE_LEFT), usable.get(sensors_pb2.LANE_SIDE_RIGHT)
    if left is not None and right is not None:
        width_m, centre_c0 = left.c0_m - right.c0_m, (left.c0_m + right.c0_m) / 2.0
        slope, curvature = (left.c1 + right.c1) / 2.0, left.c2_1pm + right.c2_1pm
        quality = min(left.quality, right.quality)
    elif fallback_width_m and (left is not None or right is not None):
        marking = left if left is not None else right
        sign = 1.0 if marking is left else -1.0
        width_m, centre_c0 = fallback_width_m, marking.c0_m - sign * fallback_width_m / 2.0
        slope, curvature, quality = marking.c1, 2.0 * marking.c2_1pm, marking.quality
    else:
        return None
    if not config.min_lane_width_m <= width_m <= config.max_lane_width_m:
        return None
    heading_error_rad = -math.atan(slope)
    age_s = max(0.0, time_s - markings.time_s)
    offset_m = lateral_offset_after_m(-centre_c0, speed_mps, heading_error_rad, age_s)
    return LaneView(offset_m, config.camera_offset_std_m / quality, heading_error_rad,
                    config.camera_heading_std_rad / quality, width_m, curvature)


def inverse_variance(a: float, a_std: float, b: float, b_std: float) -> tuple[float, float]:
    """The minimum-variance combination of two independent measurements of one quantity, and its std."""
    wa, wb = 1.0 / a_std ** 2, 1.0 / b_std ** 2
    return (wa * a + wb * b) / (wa + wb), math.sqrt(1.0 / (wa + wb))


class EgoLaneFusion:
    def __init__(self, config: LaneFusionConfig | None = None) -> None:
        self.config = config or LaneFusionConfig()
        # The camera's lane index, once map and camera agreed; its last offset, to see the car cross a line.
        self._camera_lane_index: int | None = None
        self._last_camera_offset_m: float | None = None
        self._last_markings_time_s: float | None = None
        self.disagreements = 0

    def ego_lane(self, ego: ego_pb2.EgoState | None, markings: LaneMarkings | None,
                 time_s: float) -> scene_pb2.EgoLane:
        out = scene_pb2.EgoLane()
        if ego is None:
            return out
        cfg = self.config
        mapped = map_view(ego, cfg, time_s)
        camera = None
        if markings is not None and time_s - markings.time_s <= cfg.max_marking_age_s:
            camera = camera_view(markings, cfg, mapped.lane_width_m if mapped else None, ego.speed_mps, time_s)
        if camera is None:
            self._camera_lane_index = self._last_camera_offset_m = None
            if mapped is not None:
                self._fill(out, ego.lane.lane_index, mapped, scene_pb2.LANE_SOURCE_MAP)
            return out
        self._count_crossing(camera, markings.time_s)
        if mapped is None:
            if self._camera_lane_index is not None:
                self._fill(out, self._camera_lane_index, camera, scene_pb2.LANE_SOURCE_CAMERA)
            return out
        return self._with_both(out, ego.lane.lane_index, mapped, camera)

    def _count_crossing(self, camera: LaneView, markings_time_s: float) -> None:
        """A new frame whose offset jumped by about a lane width: the camera now sees the next lane's lines."""
        if markings_time_s == self._last_markings_time_s:
            return
        last = self._last_camera_offset_m
        if last is not None and self._camera_lane_index is not None:
            lanes_moved = round((last - camera.lateral_offset_m) / camera.lane_width_m)
            self._camera_lane_index += lanes_moved
        self._last_camera_offset_m, self._last_markings_time_s = camera.lateral_offset_m, markings_time_s

    def _with_both(self, out: scene_pb2.EgoLane, map_lane_index: int, mapped: LaneView,
                   camera: LaneView) -> scene_pb2.EgoLane:
        cfg = self.config
        width_m = mapped.lane_width_m
        # The map's offset counted from the nearest lane centre the camera could be seeing.
        lanes_apart = round((mapped.lateral_offset_m - camera.lateral_offset_m) / width_m)
        if self._camera_lane_index is None:
            self._camera_lane_index = map_lane_index + lanes_apart
        map_offset_in_camera_lane_m = mapped.lateral_offset_m + (map_lane_index - self._camera_lane_index) * width_m
        difference_m = map_offset_in_camera_lane_m - camera.lateral_offset_m
        out.map_minus_camera_offset_m = difference_m
        if abs(difference_m) > cfg.gate_sigma * math.hypot(mapped.offset_std_m, camera.offset_std_m):
            self.disagreements += 1
            self._fill(out, self._camera_lane_index, camera, scene_pb2.LANE_SOURCE_CAMERA)
            return out
        offset_m, offset_std_m = inverse_variance(map_offset_in_camera_lane_m, mapped.offset_std_m,
                                                  camera.lateral_offset_m, camera.offset_std_m)
        heading_rad, heading_std = inverse_variance(mapped.heading_error_rad, mapped.heading_std_rad,
                                                    camera.heading_error_rad, camera.heading_std_rad)
        fused = LaneView(offset_m, offset_std_m, heading_rad, heading_std, width_m, mapped.curvature_1pm)
        self._fill(out, self._camera_lane_index, fused, scene_pb2.LANE_SOURCE_FUSED)
        return out

    def _fill(self, out: scene_pb2.EgoLane, lane_index: int, view: LaneView, source: int) -> None:
        out.valid, out.lane_index, out.source = True, lane_index, source
        out.lateral_offset_m, out.lateral_offset_std_m = view.lateral_offset_m, view.offset_std_m
        out.heading_error_rad, out.curvature_1pm, out.lane_width_m = (view.heading_error_rad, view.curvature_1pm,
                                                                      view.lane_width_m)
        confidence = max(0.0, 1.0 - view.offset_std_m / (view.lane_width_m / 2.0))
        slope, c2 = -math.tan(view.heading_error_rad), view.curvature_1pm / 2.0
        for boundary, sign in ((out.left, 1.0), (out.right, -1.0)):
            boundary.c0_m = -view.lateral_offset_m + sign * view.lane_width_m / 2.0
            boundary.c1, boundary.c2_1pm = slope, c2
            boundary.view_range_m, boundary.confidence = self.config.boundary_view_range_m, confidence
