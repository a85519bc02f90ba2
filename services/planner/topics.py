"""The topics the planner publishes and reads (read by the framework's topic registry: imports only messages)."""

from coopdrive.bus.topic import Topic
from coopdrive.v1 import planner_pb2

PUBLISHER = "planner"

PUBLISHES = (
    Topic("planner/state", planner_pb2.PlannerState, PUBLISHER),
    Topic("planner/behaviour", planner_pb2.BehaviourRequest, PUBLISHER),
)

SUBSCRIBES = ("ego/state", "gateway/planner_force", "scene", "v2x/cam", "v2x/denm", "v2x/iclcm")
