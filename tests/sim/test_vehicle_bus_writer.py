"""VehicleBusWriter: a simulated car's CAN bus carries its feedback and radar as DBC frames at the time they
reach the bus, with rolling counters that run on from step to step, and error frames during a burst."""

import pytest

from coopdrive.can import frames
from coopdrive.can.codec import VehicleCanCodec
from coopdrive.can.wire import to_protobuf, to_python_can
from coopdrive.services.sim.vehicle_bus_writer import VehicleBusWriter
from coopdrive.v1 import sensors_pb2, vehicle_pb2

STEP_S = 0.01


def can_state(speed_mps: float, on_bus_s: float) -> vehicle_pb2.VehicleCanState:
    state = vehicle_pb2.VehicleCanState(wheel_speed_rear_left_mps=speed_mps, wheel_speed_rear_right_mps=speed_mps)
    state.header.sent_time_s = on_bus_s
    return state


def radar(range_m: float, on_bus_s: float) -> sensors_pb2.RadarTracks:
    tracks = sensors_pb2.RadarTracks(tracks=[sensors_pb2.RadarTrack(track_id=1, range_m=range_m, width_m=1.8)])
    tracks.header.sent_time_s = on_bus_s
    return tracks


def test_a_step_s_feedback_imu_and_object_list_are_dbc_frames_in_bus_order_stamped_when_they_reach_the_bus():
    imu = vehicle_pb2.ImuSample(accel_longitudinal_mps2=0.7)
    imu.header.sent_time_s = 1.0
    batch = VehicleBusWriter().frames(1.0, STEP_S, [can_state(20.0, 0.995)], [radar(30.0, 0.99)], [imu])
    assert [f.timestamp_s for f in batch.frames] == sorted(f.timestamp_s for f in batch.frames)
    names = [frames.frame_by_id(f.arbitration_id) for f in batch.frames]
    assert names == [*frames.RADAR_FRAMES, *frames.FEEDBACK_FRAMES, *frames.INERTIAL_FRAMES]
    assert VehicleCanCodec().decode_imu_sample(to_python_can(batch.frames[-1])).accel_longitudinal_mps2 == \
        pytest.approx(0.7, abs=1e-3)
    decoder = VehicleCanCodec()
    decoded = [decoder.decode_radar(to_python_can(f)) for f in batch.frames[:2]]
    [state] = [s for s in (decoder.decode_vehicle_state(to_python_can(f)) for f in batch.frames[2:5]) if s]
    assert decoded[-1].tracks[0].range_m == pytest.approx(30.0, abs=0.15)
    assert state.wheel_speed_rear_left_mps == pytest.approx(20.0, abs=0.01)
    assert state.header.sample_time_s == 0.995


def test_the_rolling_counters_run_on_from_step_to_step_so_a_receiver_rejects_nothing():
    writer, decoder = VehicleBusWriter(), VehicleCanCodec()
    states = []
    for k in range(40):
        for frame in writer.frames(k * STEP_S, STEP_S, [can_state(10.0 + k * 0.1, k * STEP_S)]).frames:
            states.append(decoder.decode_vehicle_state(to_python_can(frame)))
    assert sum(s is not None for s in states) == 40
    assert not decoder.rejected


def test_an_error_burst_puts_its_rate_of_error_frames_on_the_bus_and_a_quiet_step_puts_nothing():
    writer = VehicleBusWriter()
    bursts = [writer.frames(k * STEP_S, STEP_S, error_frames_per_s=333.0) for k in range(100)]
    assert sum(len(b.frames) for b in bursts if b) == 333
    assert all(f.is_error_frame for b in bursts if b for f in b.frames)
    assert writer.frames(1.0, STEP_S) is None


def test_the_frames_made_straight_as_bus_frames_are_python_can_s_messages_converted_field_for_field():
    imu = vehicle_pb2.ImuSample(accel_longitudinal_mps2=-1.5, yaw_rate_radps=0.05)
    imu.header.sent_time_s = 2.0
    writer, reference = VehicleBusWriter(), VehicleCanCodec(channel="can0")
    for k in range(3):
        batch = writer.frames(2.0, STEP_S, [can_state(15.0 + k, 1.995)], [radar(40.0 - k, 1.99)], [imu])
        messages = [*reference.encode_radar_tracks(radar(40.0 - k, 1.99), 1.99),
                    *reference.encode_vehicle_state(can_state(15.0 + k, 1.995), timestamp_s=1.995),
                    reference.encode_imu_sample(imu, 2.0)]
        assert list(batch.frames) == [to_protobuf(m) for m in messages]
