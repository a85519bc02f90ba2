"""VehicleCanPort on python-can's virtual bus with the DBC: commands out, the car's frames in, stamped with the
service's clock and logged."""

import queue
import uuid

import can
import pytest

from coopdrive.can.bus_reader import VehicleBusReader
from coopdrive.can.candump import read_candump
from coopdrive.can.codec import VehicleCanCodec, VehicleCommand
from coopdrive.can.vehicle_port import VehicleCanPort, VehicleCanPortConfig, VehicleCanPortError
from coopdrive.v1 import vehicle_pb2

WAIT_S = 2.0


SERVICE_CLOCK_S = 1234.5


@pytest.fixture
def car(tmp_path):
    """(port, the car's end of the bus, received frames, candump path)."""
    channel = f"vehicle-{uuid.uuid4().hex[:8]}"
    received: queue.Queue = queue.Queue()
    log = tmp_path / "can.log"
    port = VehicleCanPort(VehicleCanPortConfig(interface="virtual", channel=channel, candump_path=str(log)),
                          received.put, clock=lambda: SERVICE_CLOCK_S)
    car_end = can.Bus(interface="virtual", channel=channel)
    yield port, car_end, received, log
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


def test_the_cars_frames_reach_the_callback_stamped_with_the_service_clock_and_decode_to_its_state(car):
    port, car_end, received, _ = car
    sent = vehicle_pb2.VehicleCanState(wheel_speed_rear_left_mps=12.0, wheel_speed_rear_right_mps=12.2,
                                       brake_pressure_bar=3.0)
    feedback = VehicleCanCodec().encode_vehicle_state(sent, timestamp_s=7.0)
    for frame in feedback:
        car_end.send(frame)
    states = []
    reader = VehicleBusReader(on_vehicle_state=states.append)
    for _ in feedback:
        frame = received.get(timeout=WAIT_S)
        assert frame.timestamp == SERVICE_CLOCK_S
        reader.feed(frame)
    [state] = states
    assert state.wheel_speed_rear_left_mps == pytest.approx(12.0, abs=0.02)
    assert state.brake_pressure_bar == pytest.approx(3.0, abs=0.1)
    assert state.header.sample_time_s == SERVICE_CLOCK_S


def test_every_frame_in_and_out_goes_to_the_candump_log(car):
    port, car_end, received, log = car
    port.send(VehicleCanCodec().encode_vehicle_command(VehicleCommand()))
    feedback = VehicleCanCodec().encode_vehicle_state(vehicle_pb2.VehicleCanState())
    for frame in feedback:
        car_end.send(frame)
    for _ in feedback:
        received.get(timeout=WAIT_S)
    port.close()
    logged = list(read_candump(log))
    assert len(logged) == 3 + len(feedback)


def test_an_interface_that_cannot_be_opened_is_refused_naming_it():
    with pytest.raises(VehicleCanPortError, match="can_port: nosuchbus channel 'x' could not be opened"):
        VehicleCanPort(VehicleCanPortConfig(interface="nosuchbus", channel="x"), lambda frame: None)
