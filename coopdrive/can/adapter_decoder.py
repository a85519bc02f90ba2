"""AdapterDecoder: a car's frames, through its vehicle CAN adapter, become VehicleCanState and ImuSample.

A frame of an id the adapter uses is checked (length, checksum and rolling counter where the adapter and DBC
say so, DBC range of the signals used) and decoded; its quantities update the latest values. The VehicleCanState
goes out when the adapter's closing message arrives and the messages it requires have been seen; an ImuSample each
time the yaw rate's message arrives (accelerations the car does not report are NaN).
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import can
from cantools.database.can import Database, Message

from coopdrive.can import frames
from coopdrive.can.adapter import INERTIAL_QUANTITIES, STATE_QUANTITIES, ChecksumKind, VehicleCanAdapter
from coopdrive.can.codec import RANGE_TOLERANCE_STEPS
from coopdrive.can.frames import CanDecodeError, DecodeFailure
from coopdrive.v1 import vehicle_pb2

Decoded = vehicle_pb2.VehicleCanState | vehicle_pb2.ImuSample


@dataclass(frozen=True)
class _UsedMessage:
    definition: Message
    signals: frozenset[str]
    checksum_index: int | None
    counter_signal: str | None


def _checksum_index(definition: Message, name: str) -> int | None:
    """The byte the checksum fills, when the message has that signal (one whole byte, either byte order)."""
    signal = next((s for s in definition.signals if s.name == name), None)
    if signal is None:
        return None
    aligned = signal.start % frames.BITS_PER_BYTE in (0, frames.BITS_PER_BYTE - 1)
    if signal.length != frames.BITS_PER_BYTE or not aligned:
        raise ValueError(f"{definition.name}.{name}: a checksum must fill one whole byte")
    return signal.start // frames.BITS_PER_BYTE


def toyota_checksum(arbitration_id: int, data: bytes, checksum_index: int) -> int:
    """The byte sum of the id's bytes, the frame length and the data bytes but the checksum, modulo 256."""
    total = len(data) + sum(arbitration_id.to_bytes(4, "big"))
    return (total + sum(data) - data[checksum_index]) & frames.BYTE_MASK


CHECKSUMS = {ChecksumKind.COOPDRIVE: frames.checksum, ChecksumKind.TOYOTA: toyota_checksum}


class AdapterDecoder:
    def __init__(self, adapter: VehicleCanAdapter, database: Database, state: bool = True,
                 inertial: bool = True) -> None:
        """state / inertial: whether VehicleCanState / ImuSample are wanted; only their messages are used."""
        self.adapter = adapter
        self._state_wanted = state
        self._imu_message = adapter.quantities["yaw_rate"].message if inertial and adapter.has_yaw_rate_sensor \
            else None
        names = [n for n in STATE_QUANTITIES if state and n in adapter.quantities]
        names += [n for n in INERTIAL_QUANTITIES if self._imu_message is not None and n in adapter.quantities]
        wanted: dict[str, set[str]] = {}
        for name in names:
            quantity = adapter.quantities[name]
            wanted.setdefault(quantity.message, set()).update(quantity.signals)
        self._required = {adapter.closing_message, *adapter.state_requires} if state else set()
        if state and adapter.gear is not None:
            wanted.setdefault(adapter.gear.message, set()).add(adapter.gear.signal)
        for name in self._required:
            wanted.setdefault(name, set())
        self._by_id = {self._key(database.get_message_by_name(m)): self._used(database, m, s)
                       for m, s in wanted.items()}
        self._quantities_of = {m: [n for n in names if adapter.quantities[n].message == m] for m in wanted}
        self._values: dict[str, float] = {}
        self._gear = vehicle_pb2.GEAR_UNSPECIFIED
        self._seen: set[str] = set()
        self._rx_counter: dict[int, int] = {}

    @staticmethod
    def _key(definition: Message) -> tuple[int, bool]:
        return definition.frame_id, bool(definition.is_extended_frame)

    def _used(self, database: Database, name: str, signals: set[str]) -> _UsedMessage:
        definition = database.get_message_by_name(name)
        integrity = self.adapter.integrity
        checked = integrity.checksum is not ChecksumKind.NONE
        index = _checksum_index(definition, integrity.checksum_signal) if checked else None
        has_counter = integrity.counter_signal in {s.name for s in definition.signals}
        return _UsedMessage(definition, frozenset(signals), index,
                            integrity.counter_signal if checked and has_counter else None)

    def uses(self, message: can.Message) -> bool:
        return (message.arbitration_id, bool(message.is_extended_id)) in self._by_id

    def decode(self, message: can.Message) -> list[Decoded]:
        """What this frame completes (often nothing); raises CanDecodeError for a frame that cannot be trusted."""
        used = self._by_id[(message.arbitration_id, bool(message.is_extended_id))]
        definition = used.definition
        data = bytes(message.data)
        if message.is_remote_frame:
            raise CanDecodeError(DecodeFailure.NOT_A_DATA_FRAME, hex(message.arbitration_id))
        if len(data) != definition.length:
            raise CanDecodeError(DecodeFailure.WRONG_LENGTH,
                                 f"{definition.name}: {len(data)} bytes, {definition.length} expected")
        if used.checksum_index is not None:
            self._check_checksum(definition, data, used.checksum_index)
        try:
            signals = definition.decode(data, decode_choices=False, scaling=True)
        except Exception as error:  # a payload cantools cannot interpret is just another bad frame
            raise CanDecodeError(DecodeFailure.OUT_OF_RANGE, f"{definition.name}: {error}") from error
        if used.counter_signal is not None:
            self._check_counter(definition, used.counter_signal, int(signals[used.counter_signal]))
        if self.adapter.check_ranges:
            self._check_ranges(definition, used.signals, signals)
        return self._apply(definition.name, signals, message.timestamp)

    def _check_checksum(self, definition: Message, data: bytes, index: int) -> None:
        expected = CHECKSUMS[self.adapter.integrity.checksum](definition.frame_id, data, index)
        if data[index] != expected:
            raise CanDecodeError(DecodeFailure.BAD_CHECKSUM, definition.name)

    def _check_counter(self, definition: Message, name: str, counter: int) -> None:
        modulo = 1 << definition.get_signal_by_name(name).length
        previous = self._rx_counter.get(definition.frame_id)
        # Re-synchronise on the received value so one lost frame costs one rejection, not all that follow.
        self._rx_counter[definition.frame_id] = counter
        if previous is not None and counter != (previous + 1) % modulo:
            raise CanDecodeError(DecodeFailure.BAD_COUNTER, f"{definition.name}: {counter} after {previous}")

    @staticmethod
    def _check_ranges(definition: Message, used: frozenset[str], signals: dict) -> None:
        for signal in definition.signals:
            low, high = signal.minimum, signal.maximum
            # Many DBCs write [0|0] for "no range given".
            if signal.name not in used or low is None or high is None or low >= high:
                continue
            slack = RANGE_TOLERANCE_STEPS * abs(signal.scale)
            if not low - slack <= signals[signal.name] <= high + slack:
                raise CanDecodeError(DecodeFailure.OUT_OF_RANGE, f"{definition.name}.{signal.name} = "
                                                                  f"{signals[signal.name]}")

    def _apply(self, name: str, signals: dict, timestamp_s: float) -> list[Decoded]:
        for quantity in self._quantities_of[name]:
            self._values[quantity] = self.adapter.quantities[quantity].value(signals)
        gear = self.adapter.gear
        if gear is not None and gear.message == name:
            self._gear = gear.gear(signals[gear.signal])
        self._seen.add(name)
        out: list[Decoded] = []
        if self._state_wanted and name == self.adapter.closing_message and self._required <= self._seen:
            out.append(self._state(timestamp_s))
        if name == self._imu_message:
            out.append(self._imu(timestamp_s))
        return out

    def _state(self, timestamp_s: float) -> vehicle_pb2.VehicleCanState:
        v = self._values
        state = vehicle_pb2.VehicleCanState(
            wheel_speed_front_left_mps=v["wheel_speed_front_left"], wheel_speed_front_right_mps=v[
                "wheel_speed_front_right"], wheel_speed_rear_left_mps=v["wheel_speed_rear_left"],
            wheel_speed_rear_right_mps=v["wheel_speed_rear_right"], yaw_rate_radps=v.get("yaw_rate", 0.0),
            throttle_pedal_ratio=v.get("accelerator_pedal", 0.0), brake_pedal_ratio=v.get("brake_pedal", 0.0),
            brake_pressure_bar=v.get("brake_pressure", 0.0), gear=self._gear,
            vehicle_speed_mps=v.get("vehicle_speed", 0.0),
            turn_signal_left=bool(v.get("turn_signal_left")), turn_signal_right=bool(v.get("turn_signal_right")))
        wheel_angle = v.get("steering_wheel_angle", 0.0)
        state.steering_wheel_angle_rad = wheel_angle
        state.steering_angle_rad = wheel_angle / self.adapter.steering_ratio
        state.header.sample_time_s = timestamp_s
        return state

    def _imu(self, timestamp_s: float) -> vehicle_pb2.ImuSample:
        v = self._values
        sample = vehicle_pb2.ImuSample(yaw_rate_radps=v["yaw_rate"],
                                       accel_longitudinal_mps2=v.get("accel_longitudinal", math.nan),
                                       accel_lateral_mps2=v.get("accel_lateral", math.nan))
        sample.header.sample_time_s = timestamp_s
        return sample
