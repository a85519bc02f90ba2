"""The topics the planner publishes and reads (read by the framework's topic registry: imports only messages)."""

from coopdrive.bus.topic import Topic
from coopdrive.v1 import planner_pb2

PUBLISHER = "planner"

PUBLISHES = (
    Topic("planner/state", planner_pb2.PlannerState, PUBLISHER),
    Topic("planner/behaviour", planner_pb2.BehaviourRequest, PUBLISHER),
    # The traffic lights' machine, run beside the scenario's (services/planner/traffic_lights.py).
    Topic("planner/lights", planner_pb2.PlannerState, PUBLISHER),
)

SUBSCRIBES = ("ego/state", "gateway/planner_force", "scene", "v2x/cam", "v2x/denm", "v2x/iclcm", "v2x/mapem",
              "v2x/spatem")
