"""Generate the shipped maps (maps/*.geojson) from a few road parameters, so they are reproducible.

    python -m coopdrive.roadmap.build_maps [--out maps/]

Roads are laid out in ENU metres around the map origin and written as WGS84 GeoJSON.
"""

from __future__ import annotations

import argparse
import json
import math
from pathlib import Path

import numpy as np
import pymap3d

LANE_WIDTH_M = 3.5
COORD_DECIMALS = 10  # 1e-10 deg is ~0.01 mm: keeps the curvature of a 5 m polyline within 0.1 %
CURVE_STEP_M = 5.0  # chord sag at R = 2500 m is ~1 mm

# A270 Eindhoven -> Helmond, the GCDC 2016 test road: one carriageway of two lanes, straight then gently
# curving to the right (Heudiasyc: "the A270 highway curves slightly to the right").
A270_ORIGIN = (51.4715, 5.6010, 20.0)
A270_START_HEADING_RAD = math.radians(10.0)
A270_STRAIGHT_M = 2500.0
A270_CURVE_M = 1500.0
A270_CURVE_RADIUS_M = 2500.0
A270_SPEED_LIMIT_MPS = 100.0 / 3.6
A270_MERGE_ZONE = ("merge_zone", 1500.0, 500.0)  # name, reference-line station, radius

# T-intersection (GCDC intersection scenario): main road east-west, side road joining from the south.
INTERSECTION_ORIGIN = (51.4690, 5.6380, 20.0)
# The main road runs this far towards the intersection on either side, and this far beyond it: a stack car of the
# intersection scenario stays on it for the whole 75 s run even at the speed limit (its cars had driven their last
# 22 s off a 300 m exit, where no map gave them a lane).
MAIN_APPROACH_LENGTH_M = 300.0
MAIN_EXIT_LENGTH_M = 850.0
SIDE_LENGTH_M = 300.0
INTERSECTION_SPEED_LIMIT_MPS = 50.0 / 3.6
# The competition-zone radius of GCDC 2016 is not in the seed papers; this value is an assumption.
COMPETITION_ZONE_RADIUS_M = 100.0

# Signalised corridor: a two-way main road east-west through two crossroads 300 m apart (an urban block), each
# crossed by a two-way side road; 50 km/h everywhere. The first crossroads is the origin.
CORRIDOR_ORIGIN = (51.4450, 5.4800, 20.0)
CORRIDOR_CROSSINGS_X_M = (0.0, 300.0)
CORRIDOR_WEST_M = 400.0
CORRIDOR_EAST_M = 1100.0
CORRIDOR_SIDE_M = 300.0


def reference_line(start_xy: tuple[float, float], heading_rad: float,
                   pieces: list[tuple[float, float]]) -> np.ndarray:
    """Poses (x, y, heading) along straight (curvature 0) and arc pieces given as (length_m, curvature_1pm)."""
    x, y, yaw = start_xy[0], start_xy[1], heading_rad
    poses = [(x, y, yaw)]
    for length_m, curvature in pieces:
        steps = 1 if curvature == 0.0 else max(1, math.ceil(length_m / CURVE_STEP_M))
        ds = length_m / steps
        for _ in range(steps):
            if curvature == 0.0:
                x, y = x + ds * math.cos(yaw), y + ds * math.sin(yaw)
            else:
                new_yaw = yaw + curvature * ds
                x += (math.sin(new_yaw) - math.sin(yaw)) / curvature
                y -= (math.cos(new_yaw) - math.cos(yaw)) / curvature
                yaw = new_yaw
            poses.append((x, y, yaw))
    return np.array(poses)


def offset_line(poses: np.ndarray, left_offset_m: float) -> np.ndarray:
    normal = np.column_stack((-np.sin(poses[:, 2]), np.cos(poses[:, 2])))
    return poses[:, :2] + left_offset_m * normal


def _geodetic(points_xy: np.ndarray, origin: tuple[float, float, float]) -> list[list[float]]:
    lat, lon, _ = pymap3d.enu2geodetic(points_xy[:, 0], points_xy[:, 1], np.zeros(len(points_xy)), *origin)
    return [[round(float(lo), COORD_DECIMALS), round(float(la), COORD_DECIMALS)] for la, lo in zip(lat, lon)]


def lane_feature(points_xy: np.ndarray, origin, road_id: str, lane_index: int, speed_limit_mps: float) -> dict:
    return {
        "type": "Feature",
        "geometry": {"type": "LineString", "coordinates": _geodetic(points_xy, origin)},
        "properties": {"road_id": road_id, "lane_id": f"{road_id}/{lane_index}", "lane_index": lane_index,
                       "width_m": LANE_WIDTH_M, "speed_limit_mps": round(speed_limit_mps, 3)},
    }


def zone_feature(x_m: float, y_m: float, origin, name: str, kind: str, radius_m: float) -> dict:
    point = _geodetic(np.array([[x_m, y_m]]), origin)[0]
    return {"type": "Feature", "geometry": {"type": "Point", "coordinates": point},
            "properties": {"kind": kind, "name": name, "radius_m": radius_m}}


def collection(name: str, origin: tuple[float, float, float], features: list[dict]) -> dict:
    return {"type": "FeatureCollection", "name": name,
            "origin": {"lat_deg": origin[0], "lon_deg": origin[1], "alt_m": origin[2]}, "features": features}


def build_a270() -> dict:
    """Reference line = boundary between the two lanes; lane 0 (right) and lane 1 (left) half a width off it."""
    poses = reference_line((0.0, 0.0), A270_START_HEADING_RAD,
                           [(A270_STRAIGHT_M, 0.0), (A270_CURVE_M, -1.0 / A270_CURVE_RADIUS_M)])
    features = [lane_feature(offset_line(poses, (index - 0.5) * LANE_WIDTH_M), A270_ORIGIN, "a270", index,
                             A270_SPEED_LIMIT_MPS) for index in (0, 1)]
    zone_name, zone_station_m, zone_radius_m = A270_MERGE_ZONE
    zx = zone_station_m * math.cos(A270_START_HEADING_RAD)
    zy = zone_station_m * math.sin(A270_START_HEADING_RAD)
    features.append(zone_feature(zx, zy, A270_ORIGIN, zone_name, "zone", zone_radius_m))
    return collection("a270", A270_ORIGIN, features)


def build_intersection() -> dict:
    """Right-hand traffic; the intersection reference point is the origin, where the centre lines cross."""
    half = 0.5 * LANE_WIDTH_M
    edge = LANE_WIDTH_M  # side-road lanes stop and start at the main road's edge
    east = np.array([[-MAIN_APPROACH_LENGTH_M, -half], [MAIN_EXIT_LENGTH_M, -half]])
    west = np.array([[MAIN_APPROACH_LENGTH_M, half], [-MAIN_EXIT_LENGTH_M, half]])
    north = np.array([[half, -SIDE_LENGTH_M], [half, -edge]])
    south = np.array([[-half, -edge], [-half, -SIDE_LENGTH_M]])
    o = INTERSECTION_ORIGIN
    speed = INTERSECTION_SPEED_LIMIT_MPS
    features = [
        lane_feature(east, o, "main_eastbound", 0, speed),
        lane_feature(west, o, "main_westbound", 0, speed),
        lane_feature(north, o, "side_northbound", 0, speed),
        lane_feature(south, o, "side_southbound", 0, speed),
        zone_feature(0.0, 0.0, o, "intersection_reference_point", "reference_point", 0.0),
        zone_feature(0.0, 0.0, o, "competition_zone", "zone", COMPETITION_ZONE_RADIUS_M),
    ]
    return collection("intersection", o, features)


def build_corridor() -> dict:
    """Right-hand traffic; each crossroads' reference point is where the centre lines cross. Lanes run straight
    through the crossroads (their stop lines and boxes are the scenario's: scenarios/signals.yaml)."""
    half = 0.5 * LANE_WIDTH_M
    o = CORRIDOR_ORIGIN
    speed = INTERSECTION_SPEED_LIMIT_MPS
    features = [
        lane_feature(np.array([[-CORRIDOR_WEST_M, -half], [CORRIDOR_EAST_M, -half]]), o, "main_eastbound", 0, speed),
        lane_feature(np.array([[CORRIDOR_EAST_M, half], [-CORRIDOR_WEST_M, half]]), o, "main_westbound", 0, speed)]
    for name, x_m in zip("ab", CORRIDOR_CROSSINGS_X_M):
        features += [
            lane_feature(np.array([[x_m + half, -CORRIDOR_SIDE_M], [x_m + half, CORRIDOR_SIDE_M]]), o,
                         f"side_{name}_northbound", 0, speed),
            lane_feature(np.array([[x_m - half, CORRIDOR_SIDE_M], [x_m - half, -CORRIDOR_SIDE_M]]), o,
                         f"side_{name}_southbound", 0, speed),
            zone_feature(x_m, 0.0, o, f"crossroads_{name}", "reference_point", 0.0)]
    return collection("corridor", o, features)


BUILDERS = {"a270": build_a270, "intersection": build_intersection, "corridor": build_corridor}


def main(argv: list[str] | None = None) -> None:
    parser = argparse.ArgumentParser(description=__doc__)
    parser.add_argument("--out", type=Path, default=Path(__file__).resolve().parents[2] / "maps")
    args = parser.parse_args(argv)
    for name, build in BUILDERS.items():
        path = args.out / f"{name}.geojson"
        path.write_text(json.dumps(build(), indent=1) + "\n")
        print(f"wrote {path}")


if __name__ == "__main__":
    main()
