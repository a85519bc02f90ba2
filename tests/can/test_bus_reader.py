"""VehicleBusReader: the frames of the vehicle's bus become the messages a service asked for, at the time they
were measured; whatever else the bus carries is skipped or counted, never raised."""

import math

import can
import pytest

from coopdrive.can import frames
from coopdrive.can.bus_reader import VehicleBusReader
from coopdrive.can.codec import VehicleCanCodec, VehicleCommand
from coopdrive.can.wire import to_protobuf
from coopdrive.v1 import sensors_pb2, vehicle_pb2
from tests.can.rav4_drive import RAV4_ADAPTER

ON_BUS_S = 10.0


def feedback(codec: VehicleCanCodec, speed_mps: float = 12.0, on_bus_s: float = ON_BUS_S) -> list[can.Message]:
    return codec.encode_vehicle_state(vehicle_pb2.VehicleCanState(
        wheel_speed_rear_left_mps=speed_mps, wheel_speed_rear_right_mps=speed_mps, yaw_rate_radps=0.05,
        brake_pressure_bar=2.0), timestamp_s=on_bus_s)


def object_list(codec: VehicleCanCodec, on_bus_s: float = ON_BUS_S) -> list[can.Message]:
    tracks = sensors_pb2.RadarTracks(tracks=[
        sensors_pb2.RadarTrack(track_id=3, range_m=25.0, azimuth_rad=0.02, range_rate_mps=-1.5, width_m=1.8),
        sensors_pb2.RadarTrack(track_id=4, range_m=60.0, azimuth_rad=-0.05, range_rate_mps=0.5, width_m=2.5)])
    return codec.encode_radar_tracks(tracks, on_bus_s)


def test_the_feedback_frames_of_one_cycle_become_one_vehicle_state_measured_the_latency_before_the_bus():
    states = []
    reader = VehicleBusReader(on_vehicle_state=states.append, vehicle_state_latency_s=0.005)
    for frame in feedback(VehicleCanCodec()):
        reader.feed(frame)
    [state] = states
    assert state.wheel_speed_rear_left_mps == pytest.approx(12.0, abs=0.01)
    assert state.brake_pressure_bar == pytest.approx(2.0, abs=0.05)
    assert state.header.sample_time_s == pytest.approx(ON_BUS_S - 0.005)
    assert reader.counters["can_frames_received"] == len(frames.FEEDBACK_FRAMES)


def test_a_radar_object_list_becomes_radar_tracks_at_the_wire_s_resolution():
    lists = []
    reader = VehicleBusReader(on_radar_tracks=lists.append, radar_latency_s=0.05)
    for frame in object_list(VehicleCanCodec()):
        reader.feed(frame)
    [tracks] = lists
    near, far = sorted(tracks.tracks, key=lambda t: t.range_m)
    # DistLong and DistLat are in 0.2 m steps, the relative velocities in 0.25 m/s steps.
    assert near.range_m == pytest.approx(25.0, abs=0.15) and far.range_m == pytest.approx(60.0, abs=0.15)
    assert near.azimuth_rad == pytest.approx(0.02, abs=0.01)
    assert near.range_rate_mps == pytest.approx(-1.5, abs=0.2)
    assert tracks.header.sample_time_s == pytest.approx(ON_BUS_S - 0.05)


def test_frames_of_a_family_nobody_asked_for_are_counted_as_ignored_not_as_faults():
    states = []
    reader = VehicleBusReader(on_vehicle_state=states.append)
    codec = VehicleCanCodec()
    for frame in object_list(codec) + codec.encode_vehicle_command(VehicleCommand()) + feedback(codec):
        reader.feed(frame)
    assert len(states) == 1
    ignored = len(object_list(codec)) + len(frames.COMMAND_FRAMES)
    assert dict(reader.counters) == {"can_frames_received": len(frames.FEEDBACK_FRAMES),
                                     "can_frames_ignored": ignored, "can_ids_ignored": 5}


def test_unknown_malformed_and_error_frames_are_counted_by_reason_and_the_next_cycle_still_decodes():
    states = []
    reader = VehicleBusReader(on_vehicle_state=states.append)
    codec = VehicleCanCodec()
    good = feedback(codec)
    tampered = bytearray(good[0].data)
    tampered[0] ^= 0xFF
    same_id = dict(arbitration_id=good[0].arbitration_id, is_extended_id=False)
    for frame in [can.Message(arbitration_id=0x7FF, data=b"\x01\x02", is_extended_id=False),
                  can.Message(is_error_frame=True), can.Message(data=b"\x00\x01", **same_id),
                  can.Message(data=bytes(tampered), timestamp=ON_BUS_S, **same_id)]:
        reader.feed(frame)
    for frame in feedback(codec, speed_mps=13.0, on_bus_s=ON_BUS_S + 0.01):
        reader.feed(frame)
    assert reader.counters["can_frames_ignored"] == 1 and reader.counters["can_ids_ignored"] == 1
    assert reader.counters["can_error_frames"] == 1
    assert reader.counters["can_rejected_wrong_length"] == 1
    assert reader.counters["can_rejected_bad_checksum"] == 1
    assert [round(s.wheel_speed_rear_left_mps, 2) for s in states] == [13.0]


def test_frames_out_of_a_can_vehicle_batch_decode_as_the_same_frames_from_python_can_do():
    from_python_can, from_protobuf = [], []
    VehicleBusReader(on_vehicle_state=from_python_can.append).feed_all(vehicle_pb2.CanFrames())
    python_can_reader = VehicleBusReader(on_vehicle_state=from_python_can.append)
    for frame in feedback(VehicleCanCodec()):
        python_can_reader.feed(frame)
    batch = vehicle_pb2.CanFrames(frames=[to_protobuf(m) for m in feedback(VehicleCanCodec())])
    VehicleBusReader(on_vehicle_state=from_protobuf.append).feed_all(batch)
    assert from_protobuf == from_python_can and len(from_protobuf) == 1
    assert math.isclose(from_protobuf[0].header.sample_time_s, ON_BUS_S)


def test_an_inertial_frame_becomes_an_imu_sample_measured_the_latency_before_the_bus():
    samples = []
    reader = VehicleBusReader(on_imu_sample=samples.append, imu_latency_s=0.005)
    sent = vehicle_pb2.ImuSample(accel_longitudinal_mps2=-1.234, accel_lateral_mps2=0.5, yaw_rate_radps=-0.02)
    reader.feed(VehicleCanCodec().encode_imu_sample(sent, timestamp_s=ON_BUS_S))
    [sample] = samples
    assert sample.accel_longitudinal_mps2 == pytest.approx(-1.234, abs=1e-3)
    assert sample.accel_lateral_mps2 == pytest.approx(0.5, abs=1e-3)
    assert sample.yaw_rate_radps == pytest.approx(-0.02, abs=1e-4)
    assert sample.header.sample_time_s == pytest.approx(ON_BUS_S - 0.005)


def test_on_a_car_without_a_coopdrive_radar_the_rdr_frames_are_another_ecu_s_and_ignored():
    lists = []
    reader = VehicleBusReader(on_radar_tracks=lists.append, vehicle_can=RAV4_ADAPTER)
    sent = object_list(VehicleCanCodec())
    for frame in sent:
        reader.feed(frame)
    assert lists == []
    assert dict(reader.counters) == {"can_frames_ignored": len(sent), "can_ids_ignored": 2}
