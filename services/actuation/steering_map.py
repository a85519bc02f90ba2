"""SteeringMap: road-wheel angle or path curvature -> a limited road-wheel angle request.

Curvature becomes an angle through the kinematic bicycle model used by Heudiasyc (Sect. 3.3):
delta = atan(L * kappa). The request is then bounded by the actuator range, by a lateral-acceleration
limit that shrinks the range with speed, and by a rate limit so it never jumps.
"""

import math
from dataclasses import dataclass

from coopdrive.services.actuation.config import SteeringConfig

# Below this speed the lateral-acceleration limit would allow any angle; it is not applied.
MIN_SPEED_FOR_LATERAL_LIMIT_MPS = 1.0


@dataclass(frozen=True)
class SteeringRequest:
    angle_rad: float
    torque_limit_nm: float
    # True when a limit changed the requested angle.
    limited: bool


class SteeringMap:
    def __init__(self, config: SteeringConfig):
        self.config = config

    def angle_from_curvature(self, curvature_1pm: float) -> float:
        return math.atan(self.config.wheelbase_m * curvature_1pm)

    def max_angle_rad(self, speed_mps: float) -> float:
        limit = self.config.max_road_wheel_angle_rad
        speed_mps = abs(speed_mps)
        if speed_mps >= MIN_SPEED_FOR_LATERAL_LIMIT_MPS:
            max_curvature_1pm = self.config.max_lateral_accel_mps2 / speed_mps**2
            limit = min(limit, self.angle_from_curvature(max_curvature_1pm))
        return limit

    def map(self, target_angle_rad: float, previous_angle_rad: float, speed_mps: float, dt_s: float) -> SteeringRequest:
        """Limits a road-wheel angle target (positive left) given the angle requested one step earlier."""
        bound = self.max_angle_rad(speed_mps)
        angle = max(-bound, min(bound, target_angle_rad))
        max_step = self.config.max_angle_rate_radps * max(dt_s, 0.0)
        angle = max(previous_angle_rad - max_step, min(previous_angle_rad + max_step, angle))
        return SteeringRequest(angle_rad=angle, torque_limit_nm=self.config.torque_limit_nm,
                               limited=angle != target_angle_rad)

    def target_angle_rad(self, steering_angle_request_rad: float, curvature_request_1pm: float) -> float:
        if self.config.use_curvature:
            return self.angle_from_curvature(curvature_request_1pm)
        return steering_angle_request_rad
