"""The topics v2x publishes and reads (read by the framework's topic registry: imports only messages)."""

from coopdrive.bus.topic import Topic
from coopdrive.v1 import infrastructure_pb2, its_pb2, v2x_pb2

PUBLISHER = "v2x"

PUBLISHES = (
    Topic("v2x/rx", v2x_pb2.GnPacket, PUBLISHER),
    Topic("v2x/tx", v2x_pb2.GnPacket, PUBLISHER),
    Topic("v2x/status", v2x_pb2.V2xStatus, PUBLISHER),
    Topic("v2x/cam", its_pb2.CamContent, PUBLISHER),
    Topic("v2x/denm", its_pb2.DenmContent, PUBLISHER),
    Topic("v2x/iclcm", its_pb2.IclcmContent, PUBLISHER),
    Topic("v2x/spatem", infrastructure_pb2.SpatemContent, PUBLISHER),
    Topic("v2x/mapem", infrastructure_pb2.MapemContent, PUBLISHER),
    Topic("v2x/srem", infrastructure_pb2.SremContent, PUBLISHER),
    Topic("v2x/ssem", infrastructure_pb2.SsemContent, PUBLISHER),
    Topic("v2x/vam", its_pb2.VamContent, PUBLISHER),
)

# v2x/rx only under replay (the recording stands in for the radio box); radio/mark only when a lockstep run
# paces the radio link by the simulator's marks.
SUBSCRIBES = ("control/command", "ego/state", "planner/behaviour", "radio/mark", "v2x/rx")
