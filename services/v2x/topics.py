"""The topics v2x publishes and reads (read by the framework's topic registry: imports only messages)."""

from coopdrive.bus.topic import Topic
from coopdrive.v1 import its_pb2, v2x_pb2

PUBLISHER = "v2x"

PUBLISHES = (
    Topic("v2x/rx", v2x_pb2.GnPacket, PUBLISHER),
    Topic("v2x/tx", v2x_pb2.GnPacket, PUBLISHER),
    Topic("v2x/status", v2x_pb2.V2xStatus, PUBLISHER),
    Topic("v2x/cam", its_pb2.CamContent, PUBLISHER),
    Topic("v2x/denm", its_pb2.DenmContent, PUBLISHER),
    Topic("v2x/iclcm", its_pb2.IclcmContent, PUBLISHER),
)

# v2x/rx only under replay (the recording stands in for the radio box); radio/mark only when a lockstep run
# paces the radio link by the simulator's marks.
SUBSCRIBES = ("control/command", "ego/state", "planner/behaviour", "radio/mark", "v2x/rx")
