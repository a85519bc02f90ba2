"""VehicleCanCodec: coopdrive.v1 values <-> vehicle.dbc frames, with rolling counters and checksums.

Both sides use it: the actuation service encodes commands and decodes feedback and radar frames; the simulator
encodes feedback and radar frames and decodes commands. Wire units stay inside this module.
"""

import math
from collections import Counter as Tally
from collections.abc import Callable, Mapping
from dataclasses import dataclass, replace

import can
from cantools.database.can import Message

from coopdrive.can import frames
from coopdrive.can.frames import CanDecodeError, DecodeFailure, VehicleFrame
from coopdrive.can.radar import RadarFrameAssembler, encode_radar_frames
from coopdrive.can.send_schedule import CyclicSendSchedule
from coopdrive.can.wire import python_can_data_frame
from coopdrive.v1 import actuation_pb2, sensors_pb2, vehicle_pb2

# What the encoders give: python-can's Message unless the codec was made with another data_frame.
EncodedFrame = can.Message | vehicle_pb2.CanFrame
# A decoded value may sit half a resolution step beyond the DBC range through float rounding.
RANGE_TOLERANCE_STEPS = 0.5
# RDR_ObjectListStatus.MeasurementCounter is 16 bits wide.
RADAR_MEASUREMENT_COUNTER_MODULO = 1 << 16


@dataclass(frozen=True)
class VehicleCommand:
    """Everything the three ACT_ frames carry, in SI units."""

    throttle_ratio: float = 0.0
    brake_ratio: float = 0.0
    deceleration_request_mps2: float = 0.0
    longitudinal_active: bool = False
    steering_angle_request_rad: float = 0.0
    steering_torque_request_nm: float = 0.0
    lateral_active: bool = False
    indicator_left: bool = False
    indicator_right: bool = False
    hazard_lights: bool = False
    automation_active: bool = False
    driving_mode: int = actuation_pb2.DRIVING_MODE_MANUAL


def _command_signals(command: VehicleCommand) -> dict[VehicleFrame, dict[str, float]]:
    return {
        VehicleFrame.LONGITUDINAL_COMMAND: {
            "ThrottleRatio": command.throttle_ratio,
            "BrakeRatio": command.brake_ratio,
            "DecelerationRequest": command.deceleration_request_mps2,
            "LongitudinalActive": int(command.longitudinal_active),
        },
        VehicleFrame.STEERING_COMMAND: {
            "SteeringAngleRequest": command.steering_angle_request_rad,
            "SteeringTorqueRequest": command.steering_torque_request_nm,
            "LateralActive": int(command.lateral_active),
        },
        VehicleFrame.BODY_COMMAND: {
            "IndicatorLeft": int(command.indicator_left),
            "IndicatorRight": int(command.indicator_right),
            "HazardLights": int(command.hazard_lights),
            "AutomationActive": int(command.automation_active),
            "DrivingMode": int(command.driving_mode),
        },
    }


def _apply_command_frame(command: VehicleCommand, frame: VehicleFrame, s: Mapping[str, float]) -> VehicleCommand:
    if frame is VehicleFrame.LONGITUDINAL_COMMAND:
        return replace(command, throttle_ratio=s["ThrottleRatio"], brake_ratio=s["BrakeRatio"],
                       deceleration_request_mps2=s["DecelerationRequest"],
                       longitudinal_active=bool(s["LongitudinalActive"]))
    if frame is VehicleFrame.STEERING_COMMAND:
        return replace(command, steering_angle_request_rad=s["SteeringAngleRequest"],
                       steering_torque_request_nm=s["SteeringTorqueRequest"],
                       lateral_active=bool(s["LateralActive"]))
    return replace(command, indicator_left=bool(s["IndicatorLeft"]), indicator_right=bool(s["IndicatorRight"]),
                   hazard_lights=bool(s["HazardLights"]), automation_active=bool(s["AutomationActive"]),
                   driving_mode=int(s["DrivingMode"]))


def _feedback_signals(state: vehicle_pb2.VehicleCanState, driver_torque_nm: float) -> dict[VehicleFrame, dict]:
    return {
        VehicleFrame.DYNAMICS: {
            "YawRate": state.yaw_rate_radps,
            "SteeringAngle": state.steering_angle_rad,
            "DriverSteeringTorque": driver_torque_nm,
        },
        VehicleFrame.PEDALS: {
            "ThrottlePedal": state.throttle_pedal_ratio,
            "BrakePedal": state.brake_pedal_ratio,
            "BrakePressure": state.brake_pressure_bar,
            "Gear": int(state.gear),
        },
        VehicleFrame.WHEEL_SPEEDS: {
            "WheelSpeedFrontLeft": abs(state.wheel_speed_front_left_mps),
            "WheelSpeedFrontRight": abs(state.wheel_speed_front_right_mps),
            "WheelSpeedRearLeft": abs(state.wheel_speed_rear_left_mps),
            "WheelSpeedRearRight": abs(state.wheel_speed_rear_right_mps),
        },
    }


def _apply_feedback_frame(state: vehicle_pb2.VehicleCanState, frame: VehicleFrame, s: Mapping[str, float]) -> None:
    if frame is VehicleFrame.DYNAMICS:
        state.yaw_rate_radps = s["YawRate"]
        state.steering_angle_rad = s["SteeringAngle"]
    elif frame is VehicleFrame.PEDALS:
        state.throttle_pedal_ratio = s["ThrottlePedal"]
        state.brake_pedal_ratio = s["BrakePedal"]
        state.brake_pressure_bar = s["BrakePressure"]
        state.gear = int(s["Gear"])
    else:
        state.wheel_speed_front_left_mps = s["WheelSpeedFrontLeft"]
        state.wheel_speed_front_right_mps = s["WheelSpeedFrontRight"]
        state.wheel_speed_rear_left_mps = s["WheelSpeedRearLeft"]
        state.wheel_speed_rear_right_mps = s["WheelSpeedRearRight"]


class VehicleCanCodec:
    """Encodes and decodes vehicle.dbc frames; keeps per-id rolling counters and counts rejections.

    One instance per receiving or sending endpoint: counters are state.
    """

    def __init__(self, check_counter: bool = True, channel: str | None = None,
                 data_frame: Callable[[int, bytes, float, str | None], EncodedFrame] =
                 python_can_data_frame):
        """data_frame makes each frame encoded (arbitration id, payload, timestamp, channel): python-can's Message,
        or wire.protobuf_data_frame where frames go straight onto the Zenoh bus (the simulator's buses)."""
        self.check_counter = check_counter
        self.channel = channel
        self._data_frame = data_frame
        self.rejected: Tally[DecodeFailure] = Tally()
        self._tx_counter: dict[VehicleFrame, int] = {}
        self._rx_counter: dict[int, int] = {}
        self._command = VehicleCommand()
        self._state = vehicle_pb2.VehicleCanState()
        self._feedback_seen: set[VehicleFrame] = set()
        self.driver_steering_torque_nm = 0.0
        self._radar = RadarFrameAssembler()
        self._radar_measurement_counter = 0

    # ---- sending -------------------------------------------------------------------------------------------

    def encode_command(self, frame: VehicleFrame, signals: Mapping[str, float],
                       timestamp_s: float = 0.0) -> EncodedFrame:
        """Encodes one command frame, filling Counter and Checksum when it has them; out-of-range values raise
        ValueError."""
        counter = self._next_counter(frame)
        values = self._with_integrity(frame, signals, counter)
        for name, value in values.items():
            if isinstance(value, float) and not math.isfinite(value):
                raise ValueError(f"{frame}.{name} is not finite: {value}")
        try:
            data = bytearray(frames.message(frame).encode(values, strict=True))
        except Exception as error:  # cantools raises several types for range and missing-signal errors
            raise ValueError(f"{frame}: {error}") from error
        return self._sealed(frame, data, timestamp_s, counter)

    def encode_saturated(self, frame: VehicleFrame, signals: Mapping[str, float],
                         timestamp_s: float = 0.0) -> EncodedFrame:
        """Simulator side: one frame with every value saturated at its DBC range (NaN at the minimum), Counter and
        Checksum filled when it has them."""
        counter = self._next_counter(frame)
        data = frames.packer(frame).pack(self._with_integrity(frame, signals, counter))
        return self._sealed(frame, data, timestamp_s, counter)

    def _next_counter(self, frame: VehicleFrame) -> int | None:
        """The counter the frame carries next (None: it has no integrity signals); taken only when the frame is
        sealed, so a frame that fails to encode leaves no gap a receiver would reject."""
        if not frames.has_integrity_signals(frame):
            return None
        return (self._tx_counter.get(frame, -1) + 1) % frames.COUNTER_MODULO

    @staticmethod
    def _with_integrity(frame: VehicleFrame, signals: Mapping[str, float],
                        counter: int | None) -> Mapping[str, float]:
        """The values to encode: the signals, and Counter and a zero Checksum (written over once the payload is
        known) where the frame has them."""
        if counter is None:
            return signals
        return {**signals, frames.COUNTER_SIGNAL: counter, frames.CHECKSUM_SIGNAL: 0}

    def _sealed(self, frame: VehicleFrame, data: bytearray, timestamp_s: float, counter: int | None) -> EncodedFrame:
        """The frame with its checksum written over the payload and its counter taken, made by data_frame."""
        frame_id = frames.frame_id(frame)
        if counter is not None:
            index = frames.checksum_byte_index(frame)
            data[index] = frames.checksum(frame_id, bytes(data), index)
            self._tx_counter[frame] = counter
        return self._data_frame(frame_id, bytes(data), timestamp_s, self.channel)

    def encode_vehicle_command(self, command: VehicleCommand, timestamp_s: float = 0.0,
                               schedule: CyclicSendSchedule | None = None) -> list[EncodedFrame]:
        """The ACT_ frames of one actuation cycle: all three, or those `schedule` says are due."""
        signals = _command_signals(command)
        due = schedule.due(signals, timestamp_s) if schedule is not None else list(signals)
        return [self.encode_command(frame, signals[frame], timestamp_s) for frame in due]

    def encode_vehicle_state(self, state: vehicle_pb2.VehicleCanState, driver_steering_torque_nm: float = 0.0,
                             timestamp_s: float = 0.0) -> list[EncodedFrame]:
        """Simulator side: the VEH_ frames of one cycle, closing frame last; values saturate at the DBC ranges."""
        signals = _feedback_signals(state, driver_steering_torque_nm)
        return [self.encode_saturated(frame, signals[frame], timestamp_s) for frame in frames.FEEDBACK_FRAMES]

    def encode_imu_sample(self, sample: vehicle_pb2.ImuSample, timestamp_s: float = 0.0) -> EncodedFrame:
        """Simulator side: one VEH_Inertial frame; values saturate at the DBC ranges."""
        frame = VehicleFrame.INERTIAL
        signals = {"AccelLongitudinal": sample.accel_longitudinal_mps2, "AccelLateral": sample.accel_lateral_mps2,
                   "YawRate": sample.yaw_rate_radps}
        return self.encode_saturated(frame, signals, timestamp_s)

    def encode_radar_tracks(self, tracks: sensors_pb2.RadarTracks, timestamp_s: float = 0.0) -> list[EncodedFrame]:
        """Simulator side: header then one RDR_Object per track (nearest MAX_RADAR_OBJECTS only)."""
        self._radar_measurement_counter = (self._radar_measurement_counter + 1) % RADAR_MEASUREMENT_COUNTER_MODULO
        return [self.encode_saturated(frame, signals, timestamp_s)
                for frame, signals in encode_radar_frames(tracks, self._radar_measurement_counter)]

    # ---- receiving -----------------------------------------------------------------------------------------

    def decode(self, msg: can.Message | vehicle_pb2.CanFrame) -> tuple[VehicleFrame, dict[str, float]]:
        """Checks and decodes one frame; raises CanDecodeError (and counts it) when it cannot be trusted."""
        try:
            return self._decode(msg)
        except CanDecodeError as error:
            self.rejected[error.reason] += 1
            raise

    def _decode(self, msg: can.Message | vehicle_pb2.CanFrame) -> tuple[VehicleFrame, dict[str, float]]:
        if msg.is_error_frame or msg.is_remote_frame:
            raise CanDecodeError(DecodeFailure.NOT_A_DATA_FRAME, hex(msg.arbitration_id))
        frame = None if msg.is_extended_id else frames.frame_by_id(msg.arbitration_id)
        if frame is None:
            raise CanDecodeError(DecodeFailure.UNKNOWN_ID, hex(msg.arbitration_id))
        definition = frames.message(frame)
        data = bytes(msg.data)
        if len(data) != definition.length:
            raise CanDecodeError(DecodeFailure.WRONG_LENGTH, f"{frame}: {len(data)} bytes, {definition.length} expected")
        if frames.has_integrity_signals(frame):
            self._check_integrity(frame, definition.frame_id, data)
        try:
            signals = definition.decode(data, decode_choices=False, scaling=True)
        except Exception as error:  # a payload cantools cannot interpret is just another bad frame
            raise CanDecodeError(DecodeFailure.OUT_OF_RANGE, f"{frame}: {error}") from error
        self._check_ranges(frame, definition, signals)
        return frame, signals

    def _check_integrity(self, frame: VehicleFrame, arbitration_id: int, data: bytes) -> None:
        index = frames.checksum_byte_index(frame)
        if data[index] != frames.checksum(arbitration_id, data, index):
            raise CanDecodeError(DecodeFailure.BAD_CHECKSUM, str(frame))
        if not self.check_counter:
            return
        counter_signal = frames.message(frame).get_signal_by_name(frames.COUNTER_SIGNAL)
        raw = int.from_bytes(data, "little")
        counter = (raw >> counter_signal.start) & ((1 << counter_signal.length) - 1)
        previous = self._rx_counter.get(arbitration_id)
        # Re-synchronise on the received value so one lost frame costs one rejection, not all that follow.
        self._rx_counter[arbitration_id] = counter
        if previous is not None and counter != (previous + 1) % frames.COUNTER_MODULO:
            raise CanDecodeError(DecodeFailure.BAD_COUNTER, f"{frame}: {counter} after {previous}")

    @staticmethod
    def _check_ranges(frame: VehicleFrame, definition: Message, signals: Mapping[str, float]) -> None:
        for signal in definition.signals:
            value = signals[signal.name]
            slack = RANGE_TOLERANCE_STEPS * abs(signal.scale)
            if signal.minimum is not None and value < signal.minimum - slack:
                raise CanDecodeError(DecodeFailure.OUT_OF_RANGE, f"{frame}.{signal.name} = {value}")
            if signal.maximum is not None and value > signal.maximum + slack:
                raise CanDecodeError(DecodeFailure.OUT_OF_RANGE, f"{frame}.{signal.name} = {value}")

    def _decode_expecting(self, msg: can.Message | vehicle_pb2.CanFrame, family: tuple[VehicleFrame, ...]):
        frame, signals = self.decode(msg)
        if frame not in family:
            self.rejected[DecodeFailure.UNEXPECTED_FRAME] += 1
            raise CanDecodeError(DecodeFailure.UNEXPECTED_FRAME, str(frame))
        return frame, signals

    def decode_command_frame(self, frame: vehicle_pb2.CanFrame) -> VehicleCommand:
        """decode_command for an ACT_ frame as it travels on the bus (can/command).

        The protobuf frame has every field decoding reads, under python-can's names, so it is decoded as it
        is: the simulator does this three times per vehicle and step.
        """
        return self.decode_command(frame)

    def decode_command(self, msg: can.Message | vehicle_pb2.CanFrame) -> VehicleCommand:
        """Simulator side: the latest command values after applying this ACT_ frame."""
        frame, signals = self._decode_expecting(msg, frames.COMMAND_FRAMES)
        self._command = _apply_command_frame(self._command, frame, signals)
        return self._command

    def decode_vehicle_state(self, msg: can.Message) -> vehicle_pb2.VehicleCanState | None:
        """A VehicleCanState when `msg` closes a feedback cycle and every VEH_ frame has been seen, else None.

        header.sample_time_s is the closing frame's timestamp; the header's other fields are the caller's.
        """
        frame, signals = self._decode_expecting(msg, frames.FEEDBACK_FRAMES)
        _apply_feedback_frame(self._state, frame, signals)
        if frame is VehicleFrame.DYNAMICS:
            self.driver_steering_torque_nm = signals["DriverSteeringTorque"]
        self._feedback_seen.add(frame)
        if frame is not frames.FEEDBACK_CYCLE_CLOSING_FRAME or len(self._feedback_seen) < len(frames.FEEDBACK_FRAMES):
            return None
        state = vehicle_pb2.VehicleCanState()
        state.CopyFrom(self._state)
        state.header.sample_time_s = msg.timestamp
        return state

    def decode_imu_sample(self, msg: can.Message) -> vehicle_pb2.ImuSample:
        """header.sample_time_s is the frame's timestamp; the header's other fields are the caller's."""
        _, s = self._decode_expecting(msg, frames.INERTIAL_FRAMES)
        sample = vehicle_pb2.ImuSample(accel_longitudinal_mps2=s["AccelLongitudinal"],
                                       accel_lateral_mps2=s["AccelLateral"], yaw_rate_radps=s["YawRate"])
        sample.header.sample_time_s = msg.timestamp
        return sample

    def decode_radar(self, msg: can.Message) -> sensors_pb2.RadarTracks | None:
        """RadarTracks once a header and all its object frames have arrived, else None."""
        frame, signals = self._decode_expecting(msg, frames.RADAR_FRAMES)
        try:
            return self._radar.add(frame, signals, msg.timestamp)
        except CanDecodeError as error:
            self.rejected[error.reason] += 1
            raise
