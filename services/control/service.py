"""Control service: turns the behaviour request, the scene and the ego state into acceleration and steering requests.

Data handlers only keep the latest messages; the control period runs the longitudinal controller (min-select over
CACC / dCACC / ACC per target and cruise) and, when the ego state is matched to a lane, the lateral controller.
"""

from __future__ import annotations

from coopdrive.bus import Envelope
from coopdrive.runtime.service import Service, ServiceConfig
from coopdrive.services.control.config import ControlConfig, LaneSourceChoice
from coopdrive.services.control.inputs import (lane_for_steering, offset_to_target_lane_m, spacing_from_request,
                                              stop_line_target, targets_from_scene)
from coopdrive.services.control.lateral import LateralController
from coopdrive.services.control.longitudinal import LongitudinalController
from coopdrive.v1 import control_pb2, ego_pb2


class ControlServiceConfig(ServiceConfig, ControlConfig):
    """The logic's ControlConfig as the service config; period_s is the control period."""


class ControlService(Service):
    name = "control"
    Config = ControlServiceConfig

    def start(self) -> None:
        c: ControlServiceConfig = self.config
        profile = c.vehicle_profile()
        self.longitudinal = LongitudinalController(profile, c.cacc_law, c.acc_law, c.speed_law)
        self.lateral = LateralController(profile, c.lateral_law)
        self.lateral_active = False
        self.ego: ego_pb2.EgoState | None = None
        self.scene = None
        self.behaviour = None
        self.ctx.subscribe("ego/state", self.on_ego)
        self.ctx.subscribe("scene", self.on_scene)
        self.ctx.subscribe("planner/behaviour", self.on_behaviour)
        self.ctx.every(c.period_s, self.control)

    def on_ego(self, envelope: Envelope) -> None:
        self.ego = envelope.message

    def on_scene(self, envelope: Envelope) -> None:
        self.scene = envelope.message

    def on_behaviour(self, envelope: Envelope) -> None:
        self.behaviour = envelope.message

    def control(self, now_s: float) -> None:
        ego, behaviour = self.ego, self.behaviour
        if ego is None or behaviour is None:
            return
        if ego.mode == ego_pb2.LOCALISATION_MODE_LOST:
            # Without a position estimate its speed is not one either; actuation's watchdog stops the vehicle.
            self.count("skipped_ego_lost")
            return
        if self.scene is None:
            stop_line = stop_line_target(behaviour, ego.speed_mps, now_s)
            targets = [] if stop_line is None else [stop_line]
        else:
            targets = targets_from_scene(behaviour, self.scene, now_s, ego.speed_mps)
        command = control_pb2.ControlCommand()
        try:
            self.longitudinal.step(now_s, ego.speed_mps, ego.accel_mps2, targets, behaviour.desired_speed_mps,
                                   spacing_from_request(behaviour)).fill(command)
            self._steer(now_s, ego, command)
        except ValueError as error:
            self.count("skipped_invalid_input")
            self.ctx.log.warning("control step skipped: %s", error)
            return
        finally:
            self._count_rejections()
        self.ctx.publish("control/command", command, sample_time_s=ego.header.sample_time_s)

    def _steer(self, now_s: float, ego: ego_pb2.EgoState, command: control_pb2.ControlCommand) -> None:
        """Lane keeping needs the lane; without a matched lane the request is straight ahead and lateral off."""
        lane = ego.lane
        if self.config.lane_source is LaneSourceChoice.SCENE:
            lane = lane_for_steering(ego, self.scene, now_s, self.config.scene_lane_max_age_s)
        if not lane.matched:
            if self.lateral_active:
                self.lateral.reset()
                self.lateral_active = False
            command.steering_angle_request_rad = 0.0
            command.lateral_mode = control_pb2.LATERAL_MODE_OFF
            return
        self.lateral_active = True
        behaviour = self.behaviour
        self.lateral.step(now_s, ego.speed_mps, offset_to_target_lane_m(lane, behaviour), lane.heading_error_rad,
                          lane.curvature_1pm, desired_offset_m=behaviour.lateral_offset_m,
                          lane_change_duration_s=behaviour.lane_change_duration_s or None).fill(command)

    def _count_rejections(self) -> None:
        # The controllers count the targets and inputs they drop; mirror the running totals for diagnostics.
        self.counters["longitudinal_rejected_inputs"] = self.longitudinal.rejected_inputs
        self.counters["lateral_rejected_inputs"] = self.lateral.rejected_inputs
