"""The topics the gateway publishes and reads (read by the framework's topic registry: imports only messages)."""

from coopdrive.bus.topic import EVERY_OTHER_TOPIC, Topic
from coopdrive.v1 import actuation_pb2, planner_pb2

PUBLISHER = "gateway"

# The operator's commands from the HTTP API.
PUBLISHES = (
    Topic("gateway/mode_request", actuation_pb2.ModeRequest, PUBLISHER),
    Topic("gateway/estop", actuation_pb2.EmergencyStop, PUBLISHER),
    Topic("gateway/planner_force", planner_pb2.PlannerForce, PUBLISHER),
)

SUBSCRIBES = (EVERY_OTHER_TOPIC,)
