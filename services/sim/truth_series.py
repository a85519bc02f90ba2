"""Ground truth over a run as per-vehicle arrays, the judge's input."""
from __future__ import annotations

from dataclasses import dataclass, field
from typing import Iterable, Sequence

import numpy as np

from coopdrive.v1 import sim_pb2

FIELDS = ("x_m", "y_m", "heading_rad", "speed_mps", "accel_mps2", "yaw_rate_radps", "length_m", "width_m",
          "lane_index", "station_m", "lateral_offset_m")


@dataclass
class TruthSeries:
    """time_s (N,) and, per vehicle id and field, an (N,) array with NaN where the vehicle was absent."""

    time_s: np.ndarray
    values: dict[str, dict[str, np.ndarray]]
    frames: list[tuple[float, list[sim_pb2.VehicleTruth]]]
    automated: set[str]
    # Each frame's signalised approaches (stop lines and signal states); empty in a world without traffic lights.
    signals: list[Sequence[sim_pb2.SignalTruth]] = field(default_factory=list)

    @classmethod
    def from_frames(cls, frames: Iterable[tuple[float, Sequence[sim_pb2.VehicleTruth]]],
                    signals: Sequence[Sequence[sim_pb2.SignalTruth]] = ()) -> TruthSeries:
        frames = [(float(t), list(vehicles)) for t, vehicles in frames]
        ids = sorted({v.vehicle_id for _, vehicles in frames for v in vehicles})
        values = {vid: {name: np.full(len(frames), np.nan) for name in FIELDS} for vid in ids}
        automated = set()
        for index, (_, vehicles) in enumerate(frames):
            for vehicle in vehicles:
                if vehicle.automated:
                    automated.add(vehicle.vehicle_id)
                for name in FIELDS:
                    values[vehicle.vehicle_id][name][index] = getattr(vehicle, name)
        return cls(np.array([t for t, _ in frames]), values, frames, automated, list(signals))

    @classmethod
    def from_ground_truth(cls, messages: Iterable[sim_pb2.GroundTruth]) -> TruthSeries:
        messages = list(messages)
        signals = [m.signals for m in messages] if any(m.signals for m in messages) else []
        return cls.from_frames(((m.header.sample_time_s, m.vehicles) for m in messages), signals)

    def signal_frames(self) -> list[tuple[float, list[sim_pb2.VehicleTruth], Sequence[sim_pb2.SignalTruth]]]:
        """(time, vehicles, signalised approaches) of each frame; none without traffic lights."""
        return [(t, vehicles, signals) for (t, vehicles), signals in zip(self.frames, self.signals)]

    @property
    def vehicle_ids(self) -> list[str]:
        return list(self.values)

    def get(self, vehicle_id: str, name: str) -> np.ndarray:
        return self.values[vehicle_id][name]
