"""VehicleCanPort on python-can's virtual bus with the DBC: commands out, the car's feedback in, and whatever
else the bus carries counted, logged and never raised."""

import queue
import uuid

import can
import pytest

from coopdrive.can.candump import read_candump
from coopdrive.can.codec import VehicleCanCodec, VehicleCommand
from coopdrive.can.vehicle_port import VehicleCanPort, VehicleCanPortConfig, VehicleCanPortError
from coopdrive.v1 import vehicle_pb2

WAIT_S = 2.0


@pytest.fixture
def car(tmp_path):
    """(port, the car's end of the bus, received vehicle states, candump path)."""
    channel = f"vehicle-{uuid.uuid4().hex[:8]}"
    states: queue.Queue = queue.Queue()
    log = tmp_path / "can.log"
    port = VehicleCanPort(VehicleCanPortConfig(interface="virtual", channel=channel, candump_path=str(log)),
                          states.put)
    car_end = can.Bus(interface="virtual", channel=channel)
    yield port, car_end, states, log
    car_end.shutdown()
    port.close()


def test_command_frames_sent_through_the_port_decode_on_the_car_side_to_the_command(car):
    port, car_end, _, _ = car
    command = VehicleCommand(throttle_ratio=0.2, steering_angle_request_rad=0.05)
    port.send(VehicleCanCodec().encode_vehicle_command(command))
    car_codec = VehicleCanCodec()
    decoded = None
    for _ in range(3):
        decoded = car_codec.decode_command(car_end.recv(timeout=WAIT_S))
    assert decoded.throttle_ratio == pytest.approx(0.2, abs=0.01)
    assert decoded.steering_angle_request_rad == pytest.approx(0.05, abs=0.001)
    assert port.counts()["can_frames_sent"] == 3


def test_the_cars_feedback_frames_become_one_vehicle_state_per_cycle(car):
    port, car_end, states, _ = car
    sent = vehicle_pb2.VehicleCanState(wheel_speed_rear_left_mps=12.0, wheel_speed_rear_right_mps=12.2,
                                       brake_pressure_bar=3.0)
    for frame in VehicleCanCodec().encode_vehicle_state(sent):
        car_end.send(frame)
    state = states.get(timeout=WAIT_S)
    assert state.wheel_speed_rear_left_mps == pytest.approx(12.0, abs=0.02)
    assert state.brake_pressure_bar == pytest.approx(3.0, abs=0.1)


def test_unknown_malformed_and_error_frames_are_counted_and_the_port_keeps_working(car):
    port, car_end, states, _ = car
    car_end.send(can.Message(arbitration_id=0x7FF, data=b"\x01\x02"))
    car_end.send(can.Message(is_error_frame=True))
    for frame in VehicleCanCodec().encode_vehicle_state(vehicle_pb2.VehicleCanState()):
        car_end.send(frame)
    states.get(timeout=WAIT_S)
    counts = port.counts()
    assert counts["can_rejected_unknown_id"] == 1 and counts["can_error_frames"] == 1


def test_every_frame_in_and_out_goes_to_the_candump_log(car):
    port, car_end, states, log = car
    port.send(VehicleCanCodec().encode_vehicle_command(VehicleCommand()))
    feedback = VehicleCanCodec().encode_vehicle_state(vehicle_pb2.VehicleCanState())
    for frame in feedback:
        car_end.send(frame)
    states.get(timeout=WAIT_S)
    port.close()
    logged = list(read_candump(log))
    assert len(logged) == 3 + len(feedback)


def test_an_interface_that_cannot_be_opened_is_refused_naming_it():
    with pytest.raises(VehicleCanPortError, match="can_port: nosuchbus channel 'x' could not be opened"):
        VehicleCanPort(VehicleCanPortConfig(interface="nosuchbus", channel="x"), lambda state: None)
