"""python-can messages <-> coopdrive.v1 CanFrame, the form a CAN frame takes on the Zenoh bus."""

import can

from coopdrive.v1 import vehicle_pb2

# The bus topics CAN frames travel on: a car's own bus as the simulator puts it on the wire (CanFrames
# batches), and actuation's ACT_ frames (one CanFrame each).
VEHICLE_BUS_TOPIC = "can/vehicle"
COMMAND_TOPIC = "can/command"


def python_can_data_frame(arbitration_id: int, data: bytes, timestamp_s: float, channel: str | None) -> can.Message:
    """A standard-id data frame we send, as python-can's Message."""
    return can.Message(arbitration_id=arbitration_id, data=data, is_extended_id=False, timestamp=timestamp_s,
                       channel=channel, is_rx=False)


def protobuf_data_frame(arbitration_id: int, data: bytes, timestamp_s: float,
                        channel: str | None) -> vehicle_pb2.CanFrame:
    """The same frame as it travels on the Zenoh bus: to_protobuf(python_can_data_frame(...)) without the Message."""
    return vehicle_pb2.CanFrame(channel=channel or "", arbitration_id=arbitration_id, data=data,
                                timestamp_s=timestamp_s)


def to_protobuf(message: can.Message) -> vehicle_pb2.CanFrame:
    return vehicle_pb2.CanFrame(channel=message.channel or "", arbitration_id=message.arbitration_id,
                                is_extended_id=message.is_extended_id, data=bytes(message.data),
                                timestamp_s=message.timestamp, is_error_frame=message.is_error_frame,
                                is_remote_frame=message.is_remote_frame)


def to_python_can(frame: vehicle_pb2.CanFrame) -> can.Message:
    # check=False: a malformed frame must reach the decoder, which counts it, rather than raise here.
    return can.Message(timestamp=frame.timestamp_s, arbitration_id=frame.arbitration_id,
                       is_extended_id=frame.is_extended_id, data=frame.data, channel=frame.channel or None,
                       is_error_frame=frame.is_error_frame, is_remote_frame=frame.is_remote_frame, check=False)
