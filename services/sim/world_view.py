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
    ego: sim_pb2.VehicleTruth
    others: Sequence[sim_pb2.VehicleTruth]
    # vehicle_id -> sensors_pb2.ObjectClass; vehicles not listed are classed by their length.
    object_classes: Mapping[str, int] = field(default_factory=dict)

    def object_class(self, truth: sim_pb2.VehicleTruth) -> int:
        if truth.vehicle_id in self.object_classes:
            return self.object_classes[truth.vehicle_id]
        return sensors_pb2.OBJECT_CLASS_TRUCK if truth.length_m > TRUCK_MIN_LENGTH_M else sensors_pb2.OBJECT_CLASS_CAR

    def height_m(self, truth: sim_pb2.VehicleTruth) -> float:
        return HEIGHT_BY_CLASS_M[self.object_class(truth)]

    def footprints_in_ego_frame(self) -> list[np.ndarray]:
        """Corners (4 x 2) of every other vehicle in the ego frame, in the order of `others`."""
        ego = self.ego
        return [geometry.to_ego_frame(
            geometry.footprint_corners(o.x_m, o.y_m, o.heading_rad, o.length_m, o.width_m),
            ego.x_m, ego.y_m, ego.heading_rad) for o in self.others]
