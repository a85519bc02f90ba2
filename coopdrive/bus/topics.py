"""The topic registry: which message each topic carries and which service publishes it.

One publisher service per topic and vehicle is what lets the lockstep barrier order data flow
(see coopdrive.runtime.dispatcher).
"""

from dataclasses import dataclass

from google.protobuf.message import Message

from coopdrive.bus.services import SERVICE_NAMES

from coopdrive.v1 import (
    actuation_pb2,
    control_pb2,
    diagnostics_pb2,
    ego_pb2,
    gnss_pb2,
    its_pb2,
    planner_pb2,
    scene_pb2,
    sensors_pb2,
    sim_pb2,
    v2x_pb2,
    vehicle_pb2,
)


@dataclass(frozen=True)
class Topic:
    name: str
    message_type: type[Message]
    publisher: str
    # Lockstep services wait for a stepped topic's messages of a step; the others (diagnostics) are
    # only observed, so nobody waits for them and their publishers send no step markers for them.
    stepped: bool = True

    @property
    def type_name(self) -> str:
        return self.message_type.DESCRIPTOR.full_name


_ALL = [
    Topic("clock", sim_pb2.SimClock, "sim"),
    Topic("ground_truth", sim_pb2.GroundTruth, "sim"),
    Topic("result", sim_pb2.RunResult, "sim"),
    # For the launcher, which owns the processes; no service waits for it.
    Topic("service_fault", sim_pb2.ServiceFault, "sim", stepped=False),
    Topic("gnss/fix", gnss_pb2.GnssFix, "sim"),
    Topic("gnss/serial_mark", sim_pb2.WireMark, "sim"),
    Topic("radio/mark", sim_pb2.WireMark, "sim"),
    # The vehicle's CAN bus (VEH_ feedback and inertial frames, the radar's RDR_ object lists) as the simulator
    # would put it on the wire. On a vehicle there is no simulator: actuation, the owner of the car's bus,
    # publishes every frame it reads here, stamped on arrival (coopdrive/can/bus_input.py).
    Topic("can/vehicle", vehicle_pb2.CanFrames, "sim"),
    Topic("can/command", vehicle_pb2.CanFrame, "actuation"),
    Topic("lidar/scan", sensors_pb2.LidarScan, "sim"),
    Topic("camera/frame", sensors_pb2.CameraFrame, "sim"),
    Topic("sonar/ranges", sensors_pb2.SonarRanges, "sim"),
    Topic("ego/state", ego_pb2.EgoState, "geolocation"),
    Topic("ego/gnss", gnss_pb2.GnssFix, "geolocation"),
    # What the receiver's port delivered, stamped on arrival: geolocation's estimator reads this stream.
    Topic("gnss/nmea", gnss_pb2.NmeaChunk, "geolocation"),
    Topic("v2x/rx", v2x_pb2.GnPacket, "v2x"),
    Topic("v2x/tx", v2x_pb2.GnPacket, "v2x"),
    Topic("v2x/status", v2x_pb2.V2xStatus, "v2x"),
    Topic("v2x/cam", its_pb2.CamContent, "v2x"),
    Topic("v2x/denm", its_pb2.DenmContent, "v2x"),
    Topic("v2x/iclcm", its_pb2.IclcmContent, "v2x"),
    Topic("scene", scene_pb2.Scene, "scene"),
    Topic("planner/state", planner_pb2.PlannerState, "planner"),
    Topic("planner/behaviour", planner_pb2.BehaviourRequest, "planner"),
    Topic("control/command", control_pb2.ControlCommand, "control"),
    Topic("actuation/command", actuation_pb2.ActuatorCommand, "actuation"),
    Topic("actuation/status", actuation_pb2.ActuationStatus, "actuation"),
    Topic("actuation/override", actuation_pb2.OverrideEvent, "actuation"),
    Topic("gateway/mode_request", actuation_pb2.ModeRequest, "gateway"),
    Topic("gateway/estop", actuation_pb2.EmergencyStop, "gateway"),
    Topic("gateway/planner_force", planner_pb2.PlannerForce, "gateway"),
]
for _service in SERVICE_NAMES:
    _ALL.append(Topic(f"diagnostics/{_service}", diagnostics_pb2.Diagnostics, _service, stepped=False))

TOPICS: dict[str, Topic] = {topic.name: topic for topic in _ALL}


def stepped_topics_of(service: str) -> list[str]:
    """The stepped topics `service` publishes, sorted."""
    return sorted(topic.name for topic in _ALL if topic.publisher == service and topic.stepped)


def topic_named(name: str) -> Topic:
    try:
        return TOPICS[name]
    except KeyError:
        raise KeyError(f"unknown topic {name!r}; known topics: {', '.join(sorted(TOPICS))}") from None
