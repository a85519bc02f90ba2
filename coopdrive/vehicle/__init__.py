"""The vehicles, described once for every service that needs to know them (coopdrive/vehicle/description.py), and
the spacing policy the planner, control and the string-stability analysis share (spacing.py)."""

from coopdrive.vehicle.catalogue import PASSENGER_CAR, TRUCK, VEHICLES, vehicle_of
from coopdrive.vehicle.description import VehicleDescription, VehicleKind
from coopdrive.vehicle.spacing import SPACING, SpacingPolicy

__all__ = ["PASSENGER_CAR", "SPACING", "SpacingPolicy", "TRUCK", "VEHICLES", "VehicleDescription", "VehicleKind",
           "vehicle_of"]
