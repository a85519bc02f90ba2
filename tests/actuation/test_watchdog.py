import math

import pytest
from actuation_fixtures import STEP_S, control_command, engaged_actuator, run

from coopdrive.services.actuation.config import ActuationConfig, WatchdogConfig
from coopdrive.services.actuation.watchdog import StopCause, StopRamp, Watchdog, command_problem
from coopdrive.v1 import actuation_pb2

SAFE_STOP = actuation_pb2.DRIVING_MODE_SAFE_STOP


@pytest.mark.parametrize("field", ["accel_request_mps2", "steering_angle_request_rad", "curvature_request_1pm"])
@pytest.mark.parametrize("value", [math.nan, math.inf, -math.inf])
def test_a_non_finite_command_is_rejected_naming_the_field(field, value):
    cmd = control_command()
    setattr(cmd, field, value)
    assert field in command_problem(cmd, WatchdogConfig())


@pytest.mark.parametrize("accel_mps2, angle_rad", [(4.5, 0.0), (-10.5, 0.0), (0.0, 0.8), (0.0, -0.8)])
def test_an_out_of_range_command_is_rejected(accel_mps2, angle_rad):
    watchdog = Watchdog(WatchdogConfig())
    trigger = watchdog.on_command(control_command(accel_mps2, angle_rad), 0.0)
    assert trigger.reason is StopCause.INVALID_COMMAND and "outside" in trigger.detail
    assert watchdog.last_valid_command is None and watchdog.commands_rejected == 1


def test_a_command_sampled_more_than_100_ms_ago_is_rejected():
    cmd = control_command(1.0)
    cmd.header.sample_time_s = 1.0
    assert Watchdog(WatchdogConfig()).on_command(cmd, 1.15).reason is StopCause.INVALID_COMMAND


def test_commands_older_than_100_ms_trigger_a_stop():
    watchdog = Watchdog(WatchdogConfig(critical_services=[]))
    watchdog.on_command(control_command(), 0.0)
    assert watchdog.check(0.1) is None
    assert watchdog.check(0.11).reason is StopCause.COMMAND_TIMEOUT


@pytest.mark.parametrize("service", ["planner", "geolocation"])
def test_a_dead_planner_or_geolocation_triggers_a_stop(service):
    watchdog = Watchdog(WatchdogConfig())
    for name in ("planner", "geolocation"):
        watchdog.set_service_alive(name, name != service)
    watchdog.on_command(control_command(), 0.0)
    trigger = watchdog.check(0.05)
    assert trigger.reason is StopCause.SERVICE_DEAD and trigger.detail == service


def test_the_stop_ramp_falls_at_the_configured_jerk_and_holds_the_deceleration():
    ramp = StopRamp(start_accel_mps2=1.0, decel_mps2=3.0, jerk_mps3=4.0)
    values = [ramp.step(0.1) for _ in range(20)]
    assert values[:3] == pytest.approx([0.6, 0.2, -0.2])
    assert values[-1] == -3.0 and min(values) == -3.0


def test_the_stop_ramp_never_releases_a_harder_braking():
    ramp = StopRamp(start_accel_mps2=-6.0, decel_mps2=3.0, jerk_mps3=4.0)
    assert [ramp.step(0.1) for _ in range(5)] == [-6.0] * 5


def accel_history(actuator, history):
    return [s.throttle_ratio * actuator.config.pedal.accel_at_full_throttle_mps2
            - s.brake_ratio * actuator.config.pedal.decel_at_full_brake_mps2 for _, s in history]


def test_the_watchdog_stop_ramps_from_the_current_command_at_the_configured_rate_with_hazards():
    config = ActuationConfig(watchdog=WatchdogConfig(stop_decel_mps2=2.0, stop_jerk_mps3=2.0))
    actuator = engaged_actuator(config=config)
    run(actuator, 0.0, 0.5, control_command(1.0))
    history = run(actuator, 0.5, 2.5)
    modes = [s.mode for _, s in history]
    first_stop = modes.index(SAFE_STOP)
    assert "control command too old" in history[first_stop][1].last_mode_change_reason
    accels = accel_history(actuator, history)
    assert accels[first_stop - 1] == pytest.approx(1.0)
    steps = [a - b for a, b in zip(accels[first_stop - 1:], accels[first_stop:])]
    assert max(steps) == pytest.approx(2.0 * STEP_S, abs=1e-3)
    assert accels[-1] == pytest.approx(-2.0, abs=2e-3)
    assert all(s.hazard_lights for _, s in history[first_stop:])
    assert not any(s.hazard_lights for _, s in history[:first_stop])


def test_a_nan_command_while_engaged_starts_the_stop_and_is_not_applied():
    actuator = engaged_actuator()
    run(actuator, 0.0, 0.2, control_command(0.5))
    assert not actuator.on_control_command(control_command(math.nan), 0.21)
    _, status = actuator.step(0.21)
    assert status.mode == SAFE_STOP
    assert "accel_request_mps2 is nan" in status.last_mode_change_reason
    assert math.isfinite(actuator.accel_request_mps2) and actuator.accel_request_mps2 < 0.5
    assert status.frames_rejected == 1


def test_an_invalid_command_in_manual_is_counted_but_stops_nothing():
    actuator = engaged_actuator(mode=actuation_pb2.DRIVING_MODE_MANUAL)
    assert not actuator.on_control_command(control_command(99.0), 0.01)
    _, status = actuator.step(0.01)
    assert status.mode == actuation_pb2.DRIVING_MODE_MANUAL and status.frames_rejected == 1


def test_a_dead_geolocation_while_engaged_starts_a_stop():
    actuator = engaged_actuator(mode=actuation_pb2.DRIVING_MODE_COOPERATIVE)
    actuator.on_service_liveness("geolocation", False)
    actuator.on_control_command(control_command(), 0.01)
    _, status = actuator.step(0.01)
    assert status.mode == SAFE_STOP and "geolocation" in status.last_mode_change_reason


def test_an_emergency_stop_starts_at_once_at_the_emergency_jerk():
    config = ActuationConfig(watchdog=WatchdogConfig(estop_decel_mps2=4.0, estop_jerk_mps3=10.0))
    actuator = engaged_actuator(config=config)
    run(actuator, 0.0, 0.2, control_command(0.0))
    actuator.on_estop(0.2, requested_by="gateway")
    assert actuator.mode == SAFE_STOP
    history = run(actuator, 0.2, 1.0, control_command(0.0))
    accels = accel_history(actuator, history)
    assert accels[0] == pytest.approx(-10.0 * STEP_S)
    assert accels[-1] == pytest.approx(-4.0)
    assert all(s.mode == SAFE_STOP and s.hazard_lights for _, s in history)
    assert "emergency stop: gateway" in history[-1][1].last_mode_change_reason


def test_fresh_commands_do_not_end_a_safe_stop():
    actuator = engaged_actuator()
    actuator.on_estop(0.0)
    history = run(actuator, 0.0, 0.5, control_command(2.0))
    assert all(s.mode == SAFE_STOP and s.throttle_ratio == 0.0 for _, s in history)


def test_the_stop_keeps_steering_with_fresh_lateral_commands_in_autonomous():
    actuator = engaged_actuator()
    actuator.on_estop(0.0)
    history = run(actuator, 0.0, 0.5, control_command(0.0, steering_angle_rad=0.05))
    assert history[-1][1].steering_angle_rad == pytest.approx(0.05)
    assert actuator.last_command.lateral_active


@pytest.mark.skipif(not hasattr(actuation_pb2, "ActuatorCommand"), reason="ActuatorCommand not in this proto set")
def test_the_actuator_command_message_mirrors_the_frames_of_a_stop():
    actuator = engaged_actuator()
    actuator.on_estop(0.0)
    run(actuator, 0.0, 0.3, control_command(0.0))
    out = actuator.actuator_command(0.3)
    assert out.hazard_lights and out.automation_active
    assert out.brake_ratio == actuator.last_command.brake_ratio > 0.0
    assert out.accel_request_mps2 == pytest.approx(actuator.accel_request_mps2)
