"""What a sensor sees of the world at one instant: the ego truth and the other road users."""
from __future__ import annotations

from dataclasses import dataclass, field
from typing import Mapping, Sequence

import numpy as np

from coopdrive.services.sim import geometry
from coopdrive.v1 import sensors_pb2, sim_pb2

# Beyond this length a vehicle without a declared class is taken for a truck.
TRUCK_MIN_LENGTH_M = 8.0
HEIGHT_BY_CLASS_M = {
    sensors_pb2.OBJECT_CLASS_CAR: 1.5,
    sensors_pb2.OBJECT_CLASS_TRUCK: 3.8,
    sensors_pb2.OBJECT_CLASS_EMERGENCY_VEHICLE: 2.6,
    sensors_pb2.OBJECT_CLASS_OBSTACLE: 1.0,
    sensors_pb2.OBJECT_CLASS_UNSPECIFIED: 1.5,
}


@dataclass
class WorldView:
    """One vehicle's view of one instant. Every sensor of the vehicle polls the same view, so what they all need
    (the other vehicles' outlines in the ego frame, their edges) is built once and shared: read it, do not
    modify it."""

    ego: sim_pb2.VehicleTruth
    others: Sequence[sim_pb2.VehicleTruth]
    # vehicle_id -> sensors_pb2.ObjectClass; vehicles not listed are classed by their length.
    object_classes: Mapping[str, int] = field(default_factory=dict)
    # vehicle_id -> corners (4 x 2, ENU) at this instant, shared by every vehicle's view (footprints_enu);
    # vehicles not listed are outlined here.
    corners_enu: Mapping[str, np.ndarray] = field(default_factory=dict)
    _in_ego_frame: list[np.ndarray] | None = field(default=None, init=False, repr=False)
    _outlines: geometry.Outlines | None = field(default=None, init=False, repr=False)

    def object_class(self, truth: sim_pb2.VehicleTruth) -> int:
        if truth.vehicle_id in self.object_classes:
            return self.object_classes[truth.vehicle_id]
        return sensors_pb2.OBJECT_CLASS_TRUCK if truth.length_m > TRUCK_MIN_LENGTH_M else sensors_pb2.OBJECT_CLASS_CAR

    def height_m(self, truth: sim_pb2.VehicleTruth) -> float:
        return HEIGHT_BY_CLASS_M[self.object_class(truth)]

    def footprints_in_ego_frame(self) -> list[np.ndarray]:
        """Corners (4 x 2) of every other vehicle in the ego frame, in the order of `others`."""
        if self._in_ego_frame is None:
            ego = self.ego
            corners = [self._corners_enu(other) for other in self.others]
            self._in_ego_frame = []
            if corners:
                # All in one transform: the same arithmetic per point, one numpy pass instead of one per vehicle.
                local = geometry.to_ego_frame(np.concatenate(corners), ego.x_m, ego.y_m, ego.heading_rad)
                self._in_ego_frame = np.split(local, np.cumsum([len(c) for c in corners])[:-1])
        return self._in_ego_frame

    def outlines(self) -> geometry.Outlines:
        """footprints_in_ego_frame() stacked with their edges, for casting rays and finding closest points."""
        if self._outlines is None:
            self._outlines = geometry.Outlines.of(self.footprints_in_ego_frame())
        return self._outlines

    def prime(self, outlines: geometry.Outlines) -> None:
        """Take the others' outlines in the ego frame, in the order of `others`, as worked out for many views at
        once (world_views)."""
        self._outlines = outlines
        self._in_ego_frame = list(outlines.corners)

    def _corners_enu(self, truth: sim_pb2.VehicleTruth) -> np.ndarray:
        corners = self.corners_enu.get(truth.vehicle_id)
        return corners if corners is not None else footprint_enu(truth)


def world_views(truths: Sequence[sim_pb2.VehicleTruth], egos: Sequence[sim_pb2.VehicleTruth],
                object_classes: Mapping[str, int]) -> list[WorldView]:
    """The WorldView of each of egos (some of truths) at one instant, their outlines ready: every vehicle's corners
    taken into every ego's frame and edged in one numpy pass for them all, not one per view: the arithmetic of each
    point is the same either way (geometry.to_ego_frames), so each view's outlines are those it would make itself."""
    corners_enu = footprints_enu(truths)
    views = [WorldView(ego, [t for t in truths if t.vehicle_id != ego.vehicle_id], object_classes, corners_enu)
             for ego in egos]
    if len(truths) < 2 or not views:
        return views
    corners = np.stack([corners_enu[truth.vehicle_id] for truth in truths])  # (vehicle, corner, xy)
    local = geometry.to_ego_frames(corners, [(ego.x_m, ego.y_m, ego.heading_rad) for ego in egos])
    edges = geometry.Outlines.edges_of(local)
    ids = [truth.vehicle_id for truth in truths]
    for view, ego_corners, ego_edges in zip(views, local, edges):
        others = np.array([vehicle_id != view.ego.vehicle_id for vehicle_id in ids])
        view.prime(geometry.Outlines(ego_corners[others], ego_edges[others]))
    return views


def footprint_enu(truth: sim_pb2.VehicleTruth) -> np.ndarray:
    return geometry.footprint_corners(truth.x_m, truth.y_m, truth.heading_rad, truth.length_m, truth.width_m)


def footprints_enu(truths: Sequence[sim_pb2.VehicleTruth]) -> dict[str, np.ndarray]:
    """Every vehicle's corners at one instant, for the WorldViews of that instant to share."""
    return {truth.vehicle_id: footprint_enu(truth) for truth in truths}
