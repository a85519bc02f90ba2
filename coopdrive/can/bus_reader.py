"""VehicleBusReader: what one service reads from the vehicle's CAN bus, decoded with the DBC.

The VEH_ feedback frames become a VehicleCanState once per cycle, each VEH_Inertial frame an ImuSample and the
radar's RDR_ object list RadarTracks, each handed to the callback the service gave for it. Frames of a family
the service did not ask for are skipped by id without decoding; error frames and frames that cannot be trusted
are counted under their reason (`can_error_frames`, `can_rejected_<reason>`), never raised.

A frame's timestamp is when it was on the bus; a decoded message's sample time is that minus the sender's
known latency (the radar reports an object list some 50 ms after it measured it).
"""

from __future__ import annotations

from collections import Counter
from typing import Callable

import can

from coopdrive.can import frames
from coopdrive.can.codec import VehicleCanCodec
from coopdrive.can.frames import CanDecodeError, VehicleFrame
from coopdrive.can.wire import to_python_can
from coopdrive.v1 import sensors_pb2, vehicle_pb2

VehicleStateHandler = Callable[[vehicle_pb2.VehicleCanState], None]
RadarTracksHandler = Callable[[sensors_pb2.RadarTracks], None]
ImuSampleHandler = Callable[[vehicle_pb2.ImuSample], None]


class VehicleBusReader:
    def __init__(self, on_vehicle_state: VehicleStateHandler | None = None,
                 on_radar_tracks: RadarTracksHandler | None = None, on_imu_sample: ImuSampleHandler | None = None,
                 vehicle_state_latency_s: float = 0.0, radar_latency_s: float = 0.0,
                 imu_latency_s: float = 0.0) -> None:
        self.on_vehicle_state = on_vehicle_state
        self.on_radar_tracks = on_radar_tracks
        self.on_imu_sample = on_imu_sample
        self.vehicle_state_latency_s = vehicle_state_latency_s
        self.radar_latency_s = radar_latency_s
        self.imu_latency_s = imu_latency_s
        self.counters: Counter[str] = Counter()
        self._codec = VehicleCanCodec()
        self._handlers: dict[int, Callable[[can.Message], None]] = {}
        if on_vehicle_state is not None:
            self._handle(frames.FEEDBACK_FRAMES, self._on_feedback_frame)
        if on_radar_tracks is not None:
            self._handle(frames.RADAR_FRAMES, self._on_radar_frame)
        if on_imu_sample is not None:
            self._handle(frames.INERTIAL_FRAMES, self._on_inertial_frame)

    def _handle(self, family: tuple[VehicleFrame, ...], handler: Callable[[can.Message], None]) -> None:
        for frame in family:
            self._handlers[frames.message(frame).frame_id] = handler

    def feed(self, message: can.Message | vehicle_pb2.CanFrame) -> None:
        """One frame as it came off the bus (python-can) or out of a can/vehicle batch (protobuf)."""
        if isinstance(message, vehicle_pb2.CanFrame):
            message = to_python_can(message)
        if message.is_error_frame:
            self.counters["can_error_frames"] += 1
            return
        handler = None if message.is_extended_id else self._handlers.get(message.arbitration_id)
        if handler is None:
            if message.is_extended_id or frames.frame_by_id(message.arbitration_id) is None:
                self.counters["can_rejected_unknown_id"] += 1
            return
        try:
            handler(message)
        except CanDecodeError as error:
            self.counters[f"can_rejected_{error.reason.name.lower()}"] += 1
            return
        self.counters["can_frames_received"] += 1

    def feed_all(self, batch: vehicle_pb2.CanFrames) -> None:
        for frame in batch.frames:
            self.feed(frame)

    def _on_feedback_frame(self, message: can.Message) -> None:
        self._hand_on(self._codec.decode_vehicle_state(message), self.vehicle_state_latency_s, self.on_vehicle_state)

    def _on_inertial_frame(self, message: can.Message) -> None:
        self._hand_on(self._codec.decode_imu_sample(message), self.imu_latency_s, self.on_imu_sample)

    def _on_radar_frame(self, message: can.Message) -> None:
        self._hand_on(self._codec.decode_radar(message), self.radar_latency_s, self.on_radar_tracks)

    @staticmethod
    def _hand_on(decoded, latency_s: float, handler: Callable) -> None:
        """A completed message, dated back to when its sender measured it, to the service's callback."""
        if decoded is not None:
            decoded.header.sample_time_s -= latency_s
            handler(decoded)
