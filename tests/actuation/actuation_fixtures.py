"""Builders shared by the actuation tests: a vehicle, its surroundings and an engaged Actuator."""

from coopdrive.services.actuation.actuator import Actuator
from coopdrive.services.actuation.config import ActuationConfig
from coopdrive.v1 import actuation_pb2, control_pb2, ego_pb2, vehicle_pb2

ALL_SERVICES = ("geolocation", "scene", "planner", "control", "v2x")
STEP_S = 0.01


def vehicle_state(speed_mps=0.0, gear=vehicle_pb2.GEAR_DRIVE, steering_angle_rad=0.0, throttle=0.0, brake=0.0,
                  brake_pressure_bar=0.0) -> vehicle_pb2.VehicleCanState:
    return vehicle_pb2.VehicleCanState(
        wheel_speed_front_left_mps=speed_mps, wheel_speed_front_right_mps=speed_mps,
        wheel_speed_rear_left_mps=speed_mps, wheel_speed_rear_right_mps=speed_mps,
        steering_angle_rad=steering_angle_rad, throttle_pedal_ratio=throttle, brake_pedal_ratio=brake,
        brake_pressure_bar=brake_pressure_bar, gear=gear)


def control_command(accel_mps2=0.0, steering_angle_rad=0.0, curvature_1pm=0.0) -> control_pb2.ControlCommand:
    return control_pb2.ControlCommand(accel_request_mps2=accel_mps2, steering_angle_request_rad=steering_angle_rad,
                                      curvature_request_1pm=curvature_1pm)


def mode_request(mode, by="driver") -> actuation_pb2.ModeRequest:
    return actuation_pb2.ModeRequest(mode=mode, requested_by=by)


def feed_healthy_world(actuator: Actuator, now_s: float, speed_mps=0.0,
                       localisation=ego_pb2.LOCALISATION_MODE_GNSS_PRECISE) -> None:
    for name in ALL_SERVICES:
        actuator.on_service_liveness(name, True)
    actuator.on_ego_state(ego_pb2.EgoState(mode=localisation), now_s)
    actuator.on_v2x_health(True, now_s)
    actuator.on_vehicle_state(vehicle_state(speed_mps), now_s)


def engaged_actuator(mode=actuation_pb2.DRIVING_MODE_AUTONOMOUS, config: ActuationConfig | None = None,
                     accel_mps2=0.0) -> Actuator:
    """An Actuator at t = 0 in `mode`, with a healthy world and one fresh command."""
    actuator = Actuator(config)
    feed_healthy_world(actuator, 0.0)
    actuator.on_control_command(control_command(accel_mps2), 0.0)
    decision = actuator.on_mode_request(mode_request(mode), 0.0)
    assert decision.accepted, decision.unmet
    actuator.step(0.0)
    return actuator


def run(actuator: Actuator, start_s: float, end_s: float, command: control_pb2.ControlCommand | None = None,
        speed_mps: float = 10.0):
    """Steps at STEP_S, feeding the world (and `command` when given); returns the (time, status) pairs."""
    history = []
    steps = round((end_s - start_s) / STEP_S)
    for i in range(1, steps + 1):
        now_s = start_s + i * STEP_S
        for name in ALL_SERVICES:
            actuator.on_service_liveness(name, True)
        actuator.on_ego_state(ego_pb2.EgoState(mode=ego_pb2.LOCALISATION_MODE_GNSS_PRECISE), now_s)
        actuator.on_v2x_health(True, now_s)
        actuator.on_vehicle_state(vehicle_state(speed_mps, steering_angle_rad=actuator.last_command.steering_angle_request_rad
                                                if actuator.last_command else 0.0), now_s)
        if command is not None:
            actuator.on_control_command(command, now_s)
        _, status = actuator.step(now_s)
        history.append((now_s, status))
    return history
