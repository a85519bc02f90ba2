"""What a scripted vehicle's own GNSS receiver makes of its state: its CAMs carry this, not the truth, as a
real station's CAMs carry its receiver's solution (position, speed and course errors of its fix mode)."""
from __future__ import annotations

import math
from typing import Any

import numpy as np

from coopdrive.services.sim.gnss_error import GaussMarkovError, GnssEpisodes
from coopdrive.services.sim.gnss_sensor import axis_sigma_m
from coopdrive.services.sim.sensor_config import GnssConfig


class CamNoise:
    def __init__(self, config: GnssConfig, rng: np.random.Generator) -> None:
        self.config = config
        self.rng = rng
        self._error = GaussMarkovError(rng, config.error_correlation_time_s, axes=2)
        self.episodes = GnssEpisodes(config, rng)

    def apply(self, fields: dict[str, Any], time_s: float) -> dict[str, Any]:
        """The CAM fields (x_m, y_m, speed_mps, heading_rad) as the receiver reports them at time_s."""
        cfg = self.config
        # Scripted cars keep to open road in our scenarios: no obstacle-driven outages, only the open-sky episodes.
        self.episodes.update(time_s, near_obstacle=False)
        sigma_m = axis_sigma_m(self.episodes.mode(cfg.fix_mode.proto)) * cfg.accuracy_scale
        error_m = sigma_m * self._error.sample(time_s)
        jump_east_m, jump_north_m = self.episodes.offset_m
        noise = self.rng.standard_normal(2)
        noisy = dict(fields)
        noisy["x_m"] = fields["x_m"] + error_m[0] + jump_east_m
        noisy["y_m"] = fields["y_m"] + error_m[1] + jump_north_m
        noisy["speed_mps"] = max(fields["speed_mps"] + cfg.speed_sigma_mps * noise[0], 0.0)
        noisy["heading_rad"] = fields["heading_rad"] + math.radians(cfg.course_sigma_deg) * noise[1]
        return noisy
