"""The topics the simulator publishes and reads (read by the framework's topic registry: imports only messages)."""

from coopdrive.bus.topic import Topic
from coopdrive.v1 import gnss_pb2, sensors_pb2, sim_pb2, vehicle_pb2

PUBLISHER = "sim"

PUBLISHES = (
    Topic("clock", sim_pb2.SimClock, PUBLISHER),
    Topic("ground_truth", sim_pb2.GroundTruth, PUBLISHER),
    Topic("result", sim_pb2.RunResult, PUBLISHER),
    # For the launcher, which owns the processes; no service waits for it.
    Topic("service_fault", sim_pb2.ServiceFault, PUBLISHER, stepped=False),
    Topic("gnss/fix", gnss_pb2.GnssFix, PUBLISHER),
    Topic("gnss/serial_mark", sim_pb2.WireMark, PUBLISHER),
    Topic("radio/mark", sim_pb2.WireMark, PUBLISHER),
    # The vehicle's CAN bus (VEH_ feedback and inertial frames, the radar's RDR_ object lists) as the simulator
    # would put it on the wire. On a vehicle there is no simulator: actuation, the owner of the car's bus,
    # publishes every frame it reads here, stamped on arrival (coopdrive/can/bus_input.py).
    Topic("can/vehicle", vehicle_pb2.CanFrames, PUBLISHER),
    Topic("lidar/scan", sensors_pb2.LidarScan, PUBLISHER),
    Topic("camera/frame", sensors_pb2.CameraFrame, PUBLISHER),
    Topic("sonar/ranges", sensors_pb2.SonarRanges, PUBLISHER),
)

# Every stack vehicle's commands to its car, and what its v2x service hands its (simulated) radio box.
SUBSCRIBES = ("can/command", "v2x/tx")
