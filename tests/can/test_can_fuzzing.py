import can
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

from coopdrive.can import frames
from coopdrive.can.bus_reader import VehicleBusReader
from coopdrive.can.codec import VehicleCanCodec
from coopdrive.can.frames import CanDecodeError, VehicleFrame
from coopdrive.services.actuation.actuator import Actuator

KNOWN_IDS = [frames.frame_id(frame) for frame in VehicleFrame]

arbitration_ids = st.one_of(st.sampled_from(KNOWN_IDS), st.integers(0, 0x7FF), st.integers(0, 0x1FFFFFFF))
payloads = st.binary(min_size=0, max_size=8)
frames_strategy = st.builds(
    lambda arbitration_id, data, extended, remote, error: can.Message(
        arbitration_id=arbitration_id if extended else arbitration_id & 0x7FF, data=data,
        is_extended_id=extended, is_remote_frame=remote, is_error_frame=error),
    arbitration_ids, payloads, st.booleans(), st.booleans(), st.booleans())

FUZZ = settings(max_examples=150, deadline=None, suppress_health_check=[HealthCheck.too_slow])


@FUZZ
@given(st.lists(frames_strategy, min_size=1, max_size=20))
def test_random_frames_only_ever_raise_can_decode_error(messages):
    codec = VehicleCanCodec()
    for msg in messages:
        for decode in (codec.decode, codec.decode_vehicle_state, codec.decode_radar, codec.decode_command):
            try:
                decode(msg)
            except CanDecodeError:
                pass


@FUZZ
@given(st.sampled_from(frames.FEEDBACK_FRAMES + frames.RADAR_FRAMES), st.binary(min_size=8, max_size=8))
def test_random_payloads_with_a_valid_checksum_only_ever_raise_can_decode_error(frame, payload):
    definition = frames.message(frame)
    data = bytearray(payload)
    if frames.has_integrity_signals(frame):
        index = frames.checksum_byte_index(frame)
        data[index] = frames.checksum(definition.frame_id, bytes(data), index)
    msg = can.Message(arbitration_id=definition.frame_id, data=bytes(data), is_extended_id=False)
    try:
        VehicleCanCodec().decode(msg)
    except CanDecodeError:
        pass


@FUZZ
@given(st.lists(frames_strategy, min_size=1, max_size=20))
def test_a_bus_reader_feeding_the_actuator_counts_random_frames_without_raising(messages):
    actuator = Actuator()
    now_s = 0.0
    reader = VehicleBusReader(on_vehicle_state=lambda state: actuator.on_vehicle_state(state, now_s),
                              on_radar_tracks=lambda tracks: None, on_imu_sample=lambda sample: None)
    for i, msg in enumerate(messages):
        now_s = i * 0.01
        reader.feed(msg)
        actuator.step(now_s)
    # Every frame lands in exactly one counter (the distinct ignored ids are a tally beside them).
    handled = sum(n for name, n in reader.counters.items() if name != "can_ids_ignored")
    assert handled == len(messages)
