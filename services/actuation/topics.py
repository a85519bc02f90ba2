"""The topics actuation publishes and reads (read by the framework's topic registry: imports only messages)."""

from coopdrive.bus.topic import Topic
from coopdrive.v1 import actuation_pb2, vehicle_pb2

PUBLISHER = "actuation"

PUBLISHES = (
    Topic("can/command", vehicle_pb2.CanFrame, PUBLISHER),
    Topic("actuation/command", actuation_pb2.ActuatorCommand, PUBLISHER),
    Topic("actuation/status", actuation_pb2.ActuationStatus, PUBLISHER),
    Topic("actuation/override", actuation_pb2.OverrideEvent, PUBLISHER),
)

# On a vehicle there is no simulator: actuation, the owner of the car's CAN bus, puts every frame it reads on the
# simulator's can/vehicle (coopdrive/can/bus_input.py). The bus's access rules let it (coopdrive.bus.bus_grant).
PUBLISHES_ON_VEHICLE = ("can/vehicle",)

# v2x/status only with require_v2x (autonomous mode needs a working radio).
SUBSCRIBES = ("can/vehicle", "control/command", "ego/state", "gateway/estop", "gateway/mode_request", "v2x/status")
