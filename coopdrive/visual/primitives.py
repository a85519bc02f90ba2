"""Small builders of Foxglove's protobuf messages (foxglove-schemas-protobuf): poses, colours, boxes, lines, labels.

Frames: "map" is the stack's local ENU frame (x east, y north, metres about the configured WGS84 origin); each
vehicle's frame sits at its reference point with x along its heading. Heading 0 = east, counter-clockwise
positive, as everywhere in coopdrive, so a heading is a rotation about z.
"""

from __future__ import annotations

import math
from collections.abc import Iterable

from foxglove_schemas_protobuf.Color_pb2 import Color
from foxglove_schemas_protobuf.CubePrimitive_pb2 import CubePrimitive
from foxglove_schemas_protobuf.LinePrimitive_pb2 import LinePrimitive
from foxglove_schemas_protobuf.Point3_pb2 import Point3
from foxglove_schemas_protobuf.Pose_pb2 import Pose
from foxglove_schemas_protobuf.Quaternion_pb2 import Quaternion
from foxglove_schemas_protobuf.TextPrimitive_pb2 import TextPrimitive
from foxglove_schemas_protobuf.Vector3_pb2 import Vector3
from google.protobuf.timestamp_pb2 import Timestamp

from coopdrive.bus.publish_spool import NANOSECONDS

MAP_FRAME = "map"
# Boxes stand on the road: their centre is half their height up.
BOX_HEIGHT_M = 1.5
LABEL_HEIGHT_M = 2.5
LABEL_FONT_PX = 14.0


def timestamp(time_s: float) -> Timestamp:
    stamp = Timestamp()
    nanoseconds = max(0, round(time_s * NANOSECONDS))
    stamp.seconds, stamp.nanos = divmod(nanoseconds, NANOSECONDS)
    return stamp


def yaw_quaternion(heading_rad: float) -> Quaternion:
    return Quaternion(x=0.0, y=0.0, z=math.sin(heading_rad / 2.0), w=math.cos(heading_rad / 2.0))


def pose(x_m: float, y_m: float, z_m: float = 0.0, heading_rad: float = 0.0) -> Pose:
    return Pose(position=Vector3(x=x_m, y=y_m, z=z_m), orientation=yaw_quaternion(heading_rad))


def color(r: float, g: float, b: float, a: float = 1.0) -> Color:
    return Color(r=r, g=g, b=b, a=a)


def confidence_color(confidence: float) -> Color:
    """Grey for an unknown or faded estimate (confidence -1 or 0) to green for a certain one; more opaque
    the surer it is."""
    sure = min(1.0, max(0.0, confidence))
    return color(0.6 - 0.5 * sure, 0.6 + 0.3 * sure, 0.6 - 0.4 * sure, 0.25 + 0.65 * sure)


def box(x_m: float, y_m: float, heading_rad: float, length_m: float, width_m: float, fill: Color,
        rear_m: float = 0.0) -> CubePrimitive:
    """A vehicle's box about its reference point (x_m, y_m), which lies rear_m ahead of its rear face (0: the
    centre of the rear bumper, the scene's reference; a rear overhang: the rear axle, the ego's and the
    simulator's)."""
    shift_m = length_m / 2.0 - rear_m
    centre_x = x_m + shift_m * math.cos(heading_rad)
    centre_y = y_m + shift_m * math.sin(heading_rad)
    return CubePrimitive(pose=pose(centre_x, centre_y, BOX_HEIGHT_M / 2.0, heading_rad),
                         size=Vector3(x=length_m, y=width_m, z=BOX_HEIGHT_M), color=fill)


def label(x_m: float, y_m: float, text: str, fill: Color) -> TextPrimitive:
    return TextPrimitive(pose=pose(x_m, y_m, LABEL_HEIGHT_M), billboard=True, font_size=LABEL_FONT_PX,
                         scale_invariant=True, color=fill, text=text)


def line_strip(points_xy: Iterable[tuple[float, float]], fill: Color, thickness_px: float) -> LinePrimitive:
    return LinePrimitive(type=LinePrimitive.LINE_STRIP, pose=pose(0.0, 0.0), thickness=thickness_px,
                         scale_invariant=True, color=fill,
                         points=[Point3(x=float(x), y=float(y), z=0.0) for x, y in points_xy])
