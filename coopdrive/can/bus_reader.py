"""VehicleBusReader: what one service reads from the vehicle's CAN bus, decoded through the car's adapter.

The car's frames become a VehicleCanState once per cycle and an ImuSample per yaw-rate frame (through the
vehicle CAN adapter, coopdrive/can/adapter.py), and coopdrive's RDR_ object list RadarTracks, each handed to
the callback the service gave for it. Frames of ids this service does not use are not ours: counted as
`can_frames_ignored` (and their distinct ids as `can_ids_ignored`), never as faults. Error frames and frames
that cannot be trusted are counted under their reason (`can_error_frames`, `can_rejected_<reason>`), never raised.

A frame's timestamp is when it was on the bus; a decoded message's sample time is that minus the sender's
known latency (the radar reports an object list some 50 ms after it measured it).
"""

from __future__ import annotations

from collections import Counter
from pathlib import Path
from typing import Callable

import can

from coopdrive.can import frames
from coopdrive.can.adapter import load_adapter
from coopdrive.can.adapter_decoder import AdapterDecoder
from coopdrive.can.codec import VehicleCanCodec
from coopdrive.can.frames import CanDecodeError
from coopdrive.can.wire import to_python_can
from coopdrive.v1 import sensors_pb2, vehicle_pb2

# Distinct ignored ids remembered for can_ids_ignored: every standard id fits; junk extended ids stop growing it.
MAX_IGNORED_IDS_TRACKED = 4096

VehicleStateHandler = Callable[[vehicle_pb2.VehicleCanState], None]
RadarTracksHandler = Callable[[sensors_pb2.RadarTracks], None]
ImuSampleHandler = Callable[[vehicle_pb2.ImuSample], None]


class VehicleBusReader:
    def __init__(self, on_vehicle_state: VehicleStateHandler | None = None,
                 on_radar_tracks: RadarTracksHandler | None = None, on_imu_sample: ImuSampleHandler | None = None,
                 vehicle_state_latency_s: float = 0.0, radar_latency_s: float = 0.0,
                 imu_latency_s: float = 0.0, vehicle_can: str | Path | None = None) -> None:
        """vehicle_can: the car's adapter file (None: the simulator's car); VehicleCanAdapterError if unusable."""
        self.on_vehicle_state = on_vehicle_state
        self.on_radar_tracks = on_radar_tracks
        self.on_imu_sample = on_imu_sample
        self.vehicle_state_latency_s = vehicle_state_latency_s
        self.radar_latency_s = radar_latency_s
        self.imu_latency_s = imu_latency_s
        self.counters: Counter[str] = Counter()
        self._ignored_ids: set[tuple[int, bool]] = set()
        adapter, database = load_adapter(vehicle_can)
        self._car = AdapterDecoder(adapter, database, state=on_vehicle_state is not None,
                                   inertial=on_imu_sample is not None)
        self._codec = VehicleCanCodec()
        self._radar_ids: set[int] = set()
        if on_radar_tracks is not None and adapter.radar_object_list:
            self._radar_ids = {frames.frame_id(frame) for frame in frames.RADAR_FRAMES}

    def feed(self, message: can.Message | vehicle_pb2.CanFrame) -> None:
        """One frame as it came off the bus (python-can) or out of a can/vehicle batch (protobuf)."""
        if isinstance(message, vehicle_pb2.CanFrame):
            message = to_python_can(message)
        if message.is_error_frame:
            self.counters["can_error_frames"] += 1
            return
        try:
            if self._car.uses(message):
                self._hand_on_all(self._car.decode(message))
            elif not message.is_extended_id and message.arbitration_id in self._radar_ids:
                self._on_radar_frame(message)
            else:
                self._ignore(message)
                return
        except CanDecodeError as error:
            self.counters[f"can_rejected_{error.reason.name.lower()}"] += 1
            return
        self.counters["can_frames_received"] += 1

    def _ignore(self, message: can.Message) -> None:
        """Another ECU's frame: not ours to decode, and no fault."""
        self.counters["can_frames_ignored"] += 1
        key = (message.arbitration_id, bool(message.is_extended_id))
        if key not in self._ignored_ids and len(self._ignored_ids) < MAX_IGNORED_IDS_TRACKED:
            self._ignored_ids.add(key)
            self.counters["can_ids_ignored"] = len(self._ignored_ids)

    def feed_all(self, batch: vehicle_pb2.CanFrames) -> None:
        for frame in batch.frames:
            self.feed(frame)

    def _hand_on_all(self, decoded: list) -> None:
        for message in decoded:
            if isinstance(message, vehicle_pb2.ImuSample):
                self._hand_on(message, self.imu_latency_s, self.on_imu_sample)
            else:
                self._hand_on(message, self.vehicle_state_latency_s, self.on_vehicle_state)

    def _on_radar_frame(self, message: can.Message) -> None:
        self._hand_on(self._codec.decode_radar(message), self.radar_latency_s, self.on_radar_tracks)

    @staticmethod
    def _hand_on(decoded, latency_s: float, handler: Callable) -> None:
        """A completed message, dated back to when its sender measured it, to the service's callback."""
        if decoded is not None:
            decoded.header.sample_time_s -= latency_s
            handler(decoded)
