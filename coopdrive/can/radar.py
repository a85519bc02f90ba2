"""Radar object-list frames (ARS-408-like) <-> coopdrive.v1 RadarTracks.

The wire carries Cartesian positions and velocities in the sensor frame (x forward, y left); RadarTracks carries
range, azimuth and range rate. The wire has no acceleration, so decoded tracks have accel_mps2 = 0, and
RadarTrack has no class, so the decoded ObjectClass stays in the signal dictionaries only.
"""

import math
from collections.abc import Iterator, Mapping

from coopdrive.can.frames import (MAX_RADAR_OBJECTS, RADAR_INTERFACE_VERSION, CanDecodeError, DecodeFailure,
                                  VehicleFrame)
from coopdrive.v1 import sensors_pb2

OBJECT_ID_MODULO = 256
ARS_CLASS_CAR = 1


def encode_radar_frames(tracks: sensors_pb2.RadarTracks,
                        measurement_counter: int) -> Iterator[tuple[VehicleFrame, dict[str, float]]]:
    """Signals of the header and object frames; only the nearest MAX_RADAR_OBJECTS tracks, like a real radar."""
    kept = sorted(tracks.tracks, key=lambda track: track.range_m)[:MAX_RADAR_OBJECTS]
    yield VehicleFrame.RADAR_STATUS, {"NumObjects": len(kept), "MeasurementCounter": measurement_counter,
                                      "InterfaceVersion": RADAR_INTERFACE_VERSION}
    for track in kept:
        cos_az, sin_az = math.cos(track.azimuth_rad), math.sin(track.azimuth_rad)
        yield VehicleFrame.RADAR_OBJECT, {
            "ObjectId": track.track_id % OBJECT_ID_MODULO,
            "DistLong": track.range_m * cos_az,
            "DistLat": track.range_m * sin_az,
            # Only the radial velocity is known from a RadarTrack.
            "VrelLong": track.range_rate_mps * cos_az,
            "VrelLat": track.range_rate_mps * sin_az,
            "ObjectClass": ARS_CLASS_CAR,
            "Width": track.width_m,
        }


def track_from_signals(signals: Mapping[str, float]) -> sensors_pb2.RadarTrack:
    x_m, y_m = signals["DistLong"], signals["DistLat"]
    vx_mps, vy_mps = signals["VrelLong"], signals["VrelLat"]
    range_m = math.hypot(x_m, y_m)
    range_rate_mps = (x_m * vx_mps + y_m * vy_mps) / range_m if range_m > 0.0 else vx_mps
    return sensors_pb2.RadarTrack(track_id=int(signals["ObjectId"]), range_m=range_m,
                                  azimuth_rad=math.atan2(y_m, x_m), range_rate_mps=range_rate_mps,
                                  accel_mps2=0.0, width_m=signals["Width"])


class RadarFrameAssembler:
    """Collects one object list: a header announcing N objects, then N object frames."""

    def __init__(self):
        self._expected: int | None = None
        self._sample_time_s = 0.0
        self._tracks: list[sensors_pb2.RadarTrack] = []

    def add(self, frame: VehicleFrame, signals: Mapping[str, float],
            timestamp_s: float) -> sensors_pb2.RadarTracks | None:
        if frame is VehicleFrame.RADAR_STATUS:
            incomplete = self._expected is not None
            self._expected = int(signals["NumObjects"])
            self._sample_time_s = timestamp_s
            self._tracks = []
            if incomplete:
                # The new list is kept; the caller learns the previous one was cut short.
                result = self._complete()
                if result is None:
                    raise CanDecodeError(DecodeFailure.UNEXPECTED_FRAME, "radar list cut short by a new header")
                return result
            return self._complete()
        if self._expected is None:
            raise CanDecodeError(DecodeFailure.UNEXPECTED_FRAME, "radar object without a list header")
        self._tracks.append(track_from_signals(signals))
        return self._complete()

    def _complete(self) -> sensors_pb2.RadarTracks | None:
        if self._expected is None or len(self._tracks) < self._expected:
            return None
        result = sensors_pb2.RadarTracks(tracks=self._tracks)
        result.header.sample_time_s = self._sample_time_s
        self._expected = None
        self._tracks = []
        return result
