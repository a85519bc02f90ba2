"""CyclicSendSchedule: ACT_ frames go out at their DBC cycle times, and at once when they change."""

import pytest

from coopdrive.can.codec import VehicleCanCodec, VehicleCommand
from coopdrive.can.frames import VehicleFrame, frame_by_id
from coopdrive.can.send_schedule import CyclicSendSchedule

TICK_S = 0.02


def sent_frames(commands: list[VehicleCommand]) -> list[list[VehicleFrame]]:
    """The frames an actuation loop at 50 Hz puts on the bus for each command."""
    codec, schedule = VehicleCanCodec(), CyclicSendSchedule()
    return [[frame_by_id(message.arbitration_id)
             for message in codec.encode_vehicle_command(command, timestamp_s=tick * TICK_S, schedule=schedule)]
            for tick, command in enumerate(commands)]


def test_the_dbc_gives_the_command_frames_their_cycle_times():
    assert CyclicSendSchedule.cycle_time_s(VehicleFrame.LONGITUDINAL_COMMAND) == pytest.approx(0.02)
    assert CyclicSendSchedule.cycle_time_s(VehicleFrame.STEERING_COMMAND) == pytest.approx(0.02)
    assert CyclicSendSchedule.cycle_time_s(VehicleFrame.BODY_COMMAND) == pytest.approx(0.1)


def test_a_steady_command_sends_the_control_frames_every_tick_and_the_body_frame_every_fifth():
    sent = sent_frames([VehicleCommand(throttle_ratio=0.2, longitudinal_active=True)] * 20)
    assert all(VehicleFrame.LONGITUDINAL_COMMAND in tick and VehicleFrame.STEERING_COMMAND in tick for tick in sent)
    assert [tick for tick, frames in enumerate(sent) if VehicleFrame.BODY_COMMAND in frames] == [0, 5, 10, 15]


def test_a_body_signal_that_changes_goes_out_at_once():
    commands = [VehicleCommand()] * 3 + [VehicleCommand(indicator_left=True)] * 3
    sent = sent_frames(commands)
    assert VehicleFrame.BODY_COMMAND in sent[3]
    assert VehicleFrame.BODY_COMMAND not in sent[4]


def test_the_receiver_sees_an_unbroken_rolling_counter_on_the_slower_frame():
    sender, receiver, schedule = VehicleCanCodec(), VehicleCanCodec(), CyclicSendSchedule()
    decoded = VehicleCommand()
    for tick in range(30):
        for message in sender.encode_vehicle_command(VehicleCommand(hazard_lights=tick >= 12),
                                                     timestamp_s=tick * TICK_S, schedule=schedule):
            decoded = receiver.decode_command(message)
    assert not receiver.rejected
    assert decoded.hazard_lights


def test_time_running_backwards_sends_every_frame_again():
    codec, schedule = VehicleCanCodec(), CyclicSendSchedule()
    codec.encode_vehicle_command(VehicleCommand(), timestamp_s=5.0, schedule=schedule)
    assert len(codec.encode_vehicle_command(VehicleCommand(), timestamp_s=1.0, schedule=schedule)) == 3
