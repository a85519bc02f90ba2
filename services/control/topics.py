"""The topics control publishes and reads (read by the framework's topic registry: imports only messages)."""

from coopdrive.bus.topic import Topic
from coopdrive.v1 import control_pb2

PUBLISHER = "control"

PUBLISHES = (Topic("control/command", control_pb2.ControlCommand, PUBLISHER),)

SUBSCRIBES = ("ego/state", "planner/behaviour", "scene")
