"""VehicleBusWriter: one simulated car's CAN bus, as the frames its ECUs and its radar would put on the wire.

Each step's VehicleCanState samples become the VEH_ feedback frames, each ImuSample a VEH_Inertial frame and
each RadarTracks list the radar's RDR_ header and object frames, encoded with the DBC and their rolling counters and checksums; during a CAN error
burst, error frames crowd the bus at the burst's rate. A frame's timestamp is when it reaches the bus, the
sample's delivery time: a receiver subtracts the sender's latency, as it would on the vehicle.
"""

from __future__ import annotations

from collections.abc import Sequence

from coopdrive.can.codec import VehicleCanCodec
from coopdrive.can.wire import protobuf_data_frame
from coopdrive.v1 import sensors_pb2, vehicle_pb2

CHANNEL = "can0"


class VehicleBusWriter:
    def __init__(self, channel: str = CHANNEL) -> None:
        self._codec = VehicleCanCodec(channel=channel, data_frame=protobuf_data_frame)
        self.channel = channel
        # Error frames owed to the bus: a rate times a step is rarely a whole number.
        self._error_frames_due = 0.0

    def frames(self, now_s: float, step_s: float, can_states: Sequence[vehicle_pb2.VehicleCanState] = (),
               radar_tracks: Sequence[sensors_pb2.RadarTracks] = (),
               imu_samples: Sequence[vehicle_pb2.ImuSample] = (), error_frames_per_s: float = 0.0) -> vehicle_pb2.CanFrames | None:
        """The frames of one step in bus order; None when the bus stayed silent."""
        timed: list[tuple[float, vehicle_pb2.CanFrame]] = []
        for state in can_states:
            on_bus_s = state.header.sent_time_s
            timed += [(on_bus_s, frame) for frame in self._codec.encode_vehicle_state(state, timestamp_s=on_bus_s)]
        for tracks in radar_tracks:
            on_bus_s = tracks.header.sent_time_s
            timed += [(on_bus_s, frame) for frame in self._codec.encode_radar_tracks(tracks, on_bus_s)]
        for sample in imu_samples:
            on_bus_s = sample.header.sent_time_s
            timed.append((on_bus_s, self._codec.encode_imu_sample(sample, on_bus_s)))
        timed += [(now_s, frame) for frame in self._error_frames(now_s, step_s, error_frames_per_s)]
        if not timed:
            return None
        timed.sort(key=lambda item: item[0])
        return vehicle_pb2.CanFrames(frames=[frame for _, frame in timed])

    def _error_frames(self, now_s: float, step_s: float, per_s: float) -> list[vehicle_pb2.CanFrame]:
        if per_s <= 0.0:
            self._error_frames_due = 0.0
            return []
        self._error_frames_due += per_s * step_s
        count = int(self._error_frames_due)
        self._error_frames_due -= count
        return [vehicle_pb2.CanFrame(channel=self.channel, timestamp_s=now_s, is_error_frame=True)
                for _ in range(count)]
