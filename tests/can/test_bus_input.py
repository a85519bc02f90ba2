"""VehicleBusInput: under replay a configured CAN port is not opened and the frames come from can/vehicle; frames
on another time base than the service's clock (a log played into a wall-clock service) are restamped on arrival."""

import pytest

from coopdrive.bus import Envelope
from coopdrive.can.bus_input import FOREIGN_TIME_BASE_S, VehicleBusInput
from coopdrive.can.bus_reader import VehicleBusReader
from coopdrive.can.codec import VehicleCanCodec
from coopdrive.can.vehicle_port import VehicleCanPortConfig
from coopdrive.can.wire import VEHICLE_BUS_TOPIC, to_protobuf
from coopdrive.recording.replay import ReplayContext
from coopdrive.v1 import vehicle_pb2

# An interface that does not exist here: opening it would fail the test.
ABSENT_PORT = VehicleCanPortConfig(interface="socketcan", channel="coopdrive-absent-can9")


def feedback_batch(on_bus_s: float) -> vehicle_pb2.CanFrames:
    state = vehicle_pb2.VehicleCanState(wheel_speed_rear_left_mps=7.0, wheel_speed_rear_right_mps=7.0)
    frames = VehicleCanCodec().encode_vehicle_state(state, timestamp_s=on_bus_s)
    return vehicle_pb2.CanFrames(frames=[to_protobuf(frame) for frame in frames])


def replayed(now_s: float, on_bus_s: float, port: VehicleCanPortConfig | None = ABSENT_PORT):
    ctx = ReplayContext(vehicle_id="ego", service_name="geolocation")
    ctx.clock.set(now_s)
    states = []
    bus_input = VehicleBusInput(ctx, VehicleBusReader(on_vehicle_state=states.append), port)
    for _, handler in ctx.handlers[VEHICLE_BUS_TOPIC]:
        handler(Envelope("ego", VEHICLE_BUS_TOPIC, feedback_batch(on_bus_s)))
    return bus_input, states


def test_under_replay_a_configured_can_port_is_not_opened_and_the_frames_come_from_can_vehicle():
    bus_input, states = replayed(now_s=100.0, on_bus_s=99.995)
    assert bus_input.port is None
    [state] = states
    assert state.wheel_speed_rear_left_mps == pytest.approx(7.0)
    assert state.header.sample_time_s == pytest.approx(99.995)
    assert "can_frames_restamped" not in bus_input.counts()


def test_frames_stamped_on_a_log_s_time_base_are_restamped_on_arrival_instead_of_being_too_old():
    # A candump log played through the coopdrive python-can interface keeps the logger's monotonic seconds.
    bus_input, states = replayed(now_s=1_764_000_000.0, on_bus_s=46408.589503, port=None)
    [state] = states
    assert state.header.sample_time_s == pytest.approx(1_764_000_000.0)
    assert bus_input.counts()["can_frames_restamped"] == len(feedback_batch(0.0).frames)


def test_a_frame_within_the_tolerance_keeps_the_time_it_was_on_the_bus():
    on_bus_s = 500.0 - 0.9 * FOREIGN_TIME_BASE_S
    _, states = replayed(now_s=500.0, on_bus_s=on_bus_s, port=None)
    assert states[0].header.sample_time_s == pytest.approx(on_bus_s)
