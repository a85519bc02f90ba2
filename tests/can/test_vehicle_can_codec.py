import math

import can
import pytest

from coopdrive.can import frames
from coopdrive.can.codec import VehicleCanCodec, VehicleCommand
from coopdrive.can.frames import CanDecodeError, DecodeFailure, VehicleFrame
from coopdrive.v1 import actuation_pb2, sensors_pb2, vehicle_pb2


@pytest.fixture
def bus_pair():
    channel = f"codec-{id(object())}"
    sender = can.Bus(interface="virtual", channel=channel, receive_own_messages=False)
    receiver = can.Bus(interface="virtual", channel=channel, receive_own_messages=False)
    yield sender, receiver
    sender.shutdown()
    receiver.shutdown()


def through_bus(bus_pair, messages):
    sender, receiver = bus_pair
    for msg in messages:
        sender.send(msg)
    received = [receiver.recv(timeout=1.0) for _ in messages]
    assert None not in received
    return received


def test_the_dbc_ships_inside_the_package_and_names_every_frame():
    database = frames.load_database()
    assert {m.name for m in database.messages} == {f.value for f in VehicleFrame}


def test_every_command_and_feedback_frame_carries_a_counter_and_a_checksum():
    for frame in frames.COMMAND_FRAMES + frames.FEEDBACK_FRAMES:
        assert frames.has_integrity_signals(frame)


def test_a_vehicle_command_crosses_the_virtual_bus_unchanged(bus_pair):
    command = VehicleCommand(throttle_ratio=0.25, longitudinal_active=True, steering_angle_request_rad=-0.12,
                             steering_torque_request_nm=3.0, lateral_active=True, indicator_left=True,
                             hazard_lights=True, automation_active=True,
                             driving_mode=actuation_pb2.DRIVING_MODE_AUTONOMOUS)
    received = through_bus(bus_pair, VehicleCanCodec().encode_vehicle_command(command))
    rx = VehicleCanCodec()
    decoded = [rx.decode_command(msg) for msg in received][-1]
    assert decoded.throttle_ratio == pytest.approx(0.25)
    assert decoded.steering_angle_request_rad == pytest.approx(-0.12, abs=1e-4)
    assert (decoded.indicator_left, decoded.indicator_right, decoded.hazard_lights) == (True, False, True)
    assert decoded.driving_mode == actuation_pb2.DRIVING_MODE_AUTONOMOUS


def test_the_rolling_counter_advances_and_wraps_per_frame():
    codec = VehicleCanCodec()
    rx = VehicleCanCodec()
    counters = []
    for _ in range(20):
        msg = codec.encode_command(VehicleFrame.BODY_COMMAND, {"IndicatorLeft": 0, "IndicatorRight": 0,
                                                              "HazardLights": 0, "AutomationActive": 0,
                                                              "DrivingMode": 1})
        counters.append(rx.decode(msg)[1][frames.COUNTER_SIGNAL])
    assert counters == [i % 16 for i in range(20)]


def test_an_unknown_id_is_rejected():
    with pytest.raises(CanDecodeError) as error:
        VehicleCanCodec().decode(can.Message(arbitration_id=0x7FF, data=bytes(8), is_extended_id=False))
    assert error.value.reason is DecodeFailure.UNKNOWN_ID


def test_a_wrong_length_is_rejected():
    msg = VehicleCanCodec().encode_vehicle_command(VehicleCommand())[0]
    short = can.Message(arbitration_id=msg.arbitration_id, data=msg.data[:6], is_extended_id=False)
    with pytest.raises(CanDecodeError) as error:
        VehicleCanCodec().decode(short)
    assert error.value.reason is DecodeFailure.WRONG_LENGTH


def test_a_flipped_bit_fails_the_checksum_and_is_counted():
    msg = VehicleCanCodec().encode_vehicle_command(VehicleCommand(throttle_ratio=0.5))[0]
    data = bytearray(msg.data)
    data[0] ^= 0x04
    rx = VehicleCanCodec()
    with pytest.raises(CanDecodeError) as error:
        rx.decode(can.Message(arbitration_id=msg.arbitration_id, data=bytes(data), is_extended_id=False))
    assert error.value.reason is DecodeFailure.BAD_CHECKSUM
    assert rx.rejected[DecodeFailure.BAD_CHECKSUM] == 1


def test_a_repeated_or_skipped_counter_is_rejected_then_resynchronised():
    tx, rx = VehicleCanCodec(), VehicleCanCodec()
    first, second, third = (tx.encode_vehicle_command(VehicleCommand())[0] for _ in range(3))
    rx.decode(first)
    with pytest.raises(CanDecodeError) as error:
        rx.decode(first)
    assert error.value.reason is DecodeFailure.BAD_COUNTER
    with pytest.raises(CanDecodeError):
        rx.decode(third)
    assert rx.decode(tx.encode_vehicle_command(VehicleCommand())[0])[0] is VehicleFrame.LONGITUDINAL_COMMAND


def test_out_of_range_command_values_are_refused_when_encoding():
    with pytest.raises(ValueError):
        VehicleCanCodec().encode_vehicle_command(VehicleCommand(throttle_ratio=1.5))
    with pytest.raises(ValueError):
        VehicleCanCodec().encode_vehicle_command(VehicleCommand(steering_angle_request_rad=math.nan))


def test_a_well_formed_frame_with_an_out_of_range_value_is_rejected():
    codec = VehicleCanCodec()
    definition = frames.message(VehicleFrame.STEERING_COMMAND)
    data = bytearray(definition.encode({"SteeringAngleRequest": 0.0, "SteeringTorqueRequest": 0.0,
                                        "LateralActive": 0, "Counter": 0, "Checksum": 0}))
    data[0:2] = (30000).to_bytes(2, "little")  # 3.0 rad, beyond the 0.7 rad range
    data[7] = frames.checksum(definition.frame_id, bytes(data), 7)
    with pytest.raises(CanDecodeError) as error:
        codec.decode(can.Message(arbitration_id=definition.frame_id, data=bytes(data), is_extended_id=False))
    assert error.value.reason is DecodeFailure.OUT_OF_RANGE


def test_vehicle_feedback_becomes_a_vehicle_can_state_once_per_cycle(bus_pair):
    state = vehicle_pb2.VehicleCanState(
        wheel_speed_front_left_mps=13.1, wheel_speed_front_right_mps=13.2, wheel_speed_rear_left_mps=13.0,
        wheel_speed_rear_right_mps=12.9, yaw_rate_radps=-0.05, steering_angle_rad=0.02,
        throttle_pedal_ratio=0.3, brake_pedal_ratio=0.0, brake_pressure_bar=1.5, gear=vehicle_pb2.GEAR_DRIVE)
    sent = VehicleCanCodec().encode_vehicle_state(state, driver_steering_torque_nm=1.25, timestamp_s=4.0)
    assert [frames.frame_by_id(m.arbitration_id) for m in sent][-1] is frames.FEEDBACK_CYCLE_CLOSING_FRAME
    rx = VehicleCanCodec()
    results = [rx.decode_vehicle_state(msg) for msg in through_bus(bus_pair, sent)]
    assert results[:-1] == [None] * (len(sent) - 1)
    decoded = results[-1]
    assert decoded.wheel_speed_front_right_mps == pytest.approx(13.2)
    assert decoded.yaw_rate_radps == pytest.approx(-0.05, abs=1e-4)
    assert decoded.brake_pressure_bar == pytest.approx(1.5)
    assert decoded.gear == vehicle_pb2.GEAR_DRIVE
    assert rx.driver_steering_torque_nm == pytest.approx(1.25)


def test_simulated_feedback_beyond_the_wire_range_saturates_instead_of_failing():
    state = vehicle_pb2.VehicleCanState(wheel_speed_rear_left_mps=200.0, brake_pressure_bar=900.0)
    rx = VehicleCanCodec()
    decoded = [rx.decode_vehicle_state(m) for m in VehicleCanCodec().encode_vehicle_state(state)][-1]
    assert decoded.wheel_speed_rear_left_mps == pytest.approx(81.91)
    assert decoded.brake_pressure_bar == pytest.approx(400.0)


def test_radar_tracks_cross_the_bus_as_a_header_and_one_frame_per_object(bus_pair):
    tracks = sensors_pb2.RadarTracks(tracks=[
        sensors_pb2.RadarTrack(track_id=i, range_m=20.0 + 3 * i, azimuth_rad=0.01 * (i - 5),
                               range_rate_mps=-1.5, width_m=1.8) for i in range(12)])
    sent = VehicleCanCodec().encode_radar_tracks(tracks, timestamp_s=2.0)
    assert len(sent) == 13
    rx = VehicleCanCodec()
    results = [rx.decode_radar(msg) for msg in through_bus(bus_pair, sent)]
    decoded = results[-1]
    assert results[:-1] == [None] * 12
    for original, track in zip(tracks.tracks, decoded.tracks):
        assert track.track_id == original.track_id
        assert track.range_m == pytest.approx(original.range_m, abs=0.2)
        assert track.azimuth_rad == pytest.approx(original.azimuth_rad, abs=0.01)
        assert track.range_rate_mps == pytest.approx(original.range_rate_mps, abs=0.3)
        assert track.width_m == pytest.approx(1.8)


def test_the_radar_keeps_only_the_nearest_40_objects():
    tracks = sensors_pb2.RadarTracks(tracks=[sensors_pb2.RadarTrack(track_id=i, range_m=100.0 - i)
                                             for i in range(60)])
    rx = VehicleCanCodec()
    decoded = [rx.decode_radar(m) for m in VehicleCanCodec().encode_radar_tracks(tracks)][-1]
    assert len(decoded.tracks) == frames.MAX_RADAR_OBJECTS
    assert max(t.range_m for t in decoded.tracks) == pytest.approx(100.0 - 20, abs=0.2)


def test_an_empty_radar_list_is_complete_with_its_header():
    rx = VehicleCanCodec()
    [header] = VehicleCanCodec().encode_radar_tracks(sensors_pb2.RadarTracks())
    assert len(rx.decode_radar(header).tracks) == 0


def test_a_radar_object_without_a_header_is_rejected():
    objects = VehicleCanCodec().encode_radar_tracks(
        sensors_pb2.RadarTracks(tracks=[sensors_pb2.RadarTrack(track_id=1, range_m=10.0)]))[1:]
    with pytest.raises(CanDecodeError) as error:
        VehicleCanCodec().decode_radar(objects[0])
    assert error.value.reason is DecodeFailure.UNEXPECTED_FRAME


def test_a_feedback_decoder_refuses_a_command_frame():
    msg = VehicleCanCodec().encode_vehicle_command(VehicleCommand())[0]
    with pytest.raises(CanDecodeError) as error:
        VehicleCanCodec().decode_vehicle_state(msg)
    assert error.value.reason is DecodeFailure.UNEXPECTED_FRAME
