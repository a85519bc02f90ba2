"""The topics scene publishes and reads (read by the framework's topic registry: imports only messages)."""

from coopdrive.bus.topic import Topic
from coopdrive.v1 import scene_pb2

PUBLISHER = "scene"

PUBLISHES = (Topic("scene", scene_pb2.Scene, PUBLISHER),)

SUBSCRIBES = ("camera/frame", "can/vehicle", "ego/state", "lidar/scan", "sonar/ranges", "v2x/cam", "v2x/iclcm",
              "v2x/status")
