"""What every simulated sensor that delivers one message per sample shares: its timing (rate, latency, jitter,
dropout, see sensor_timing.py), the dropout fault hook, and the header stamped on each message it delivers."""
from __future__ import annotations

from typing import Callable, Generic

import numpy as np

from coopdrive.services.sim.sensor_config import SensorTimingConfig
from coopdrive.services.sim.sensor_timing import SENDER, Output, SensorTiming, stamp


class TimedSensor(Generic[Output]):
    def __init__(self, timing: SensorTimingConfig, rng: np.random.Generator, vehicle_id: str) -> None:
        self.rng = rng
        self.vehicle_id = vehicle_id
        self.timing: SensorTiming[Output] = SensorTiming(timing, rng)
        self._sequence = 0

    def set_dropout(self, active: bool) -> None:
        """Fault hook (sensor_dropout, can_error_burst): nothing is delivered while active."""
        self.timing.forced_dropout = active

    def _deliver(self, now_s: float, measure: Callable[[], Output]) -> list[Output]:
        """The messages due by now_s, each measured when it is sampled and stamped with its sample and delivery
        times and its sequence number."""
        outputs = []
        for sample_s, delivery_s, message in self.timing.poll(now_s, lambda _sample_s: measure()):
            self._sequence += 1
            stamp(message.header, sample_s, delivery_s, self.vehicle_id, SENDER, self._sequence)
            outputs.append(message)
        return outputs
