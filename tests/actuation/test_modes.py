import logging

import pytest

from coopdrive.services.actuation.config import ModesConfig
from coopdrive.services.actuation.modes import (AUTONOMOUS, COOPERATIVE, MANUAL, SAFE_STOP, Condition,
                                                DrivingModeManager)
from coopdrive.v1 import actuation_pb2, ego_pb2, vehicle_pb2

SERVICES = ("geolocation", "scene", "planner", "control", "v2x")
COMMAND_TIMEOUT_S = 0.1


def ready_manager(now_s=0.0, speed_mps=0.0) -> DrivingModeManager:
    manager = DrivingModeManager(ModesConfig(), COMMAND_TIMEOUT_S)
    feed(manager, now_s, speed_mps)
    return manager


def feed(manager, now_s, speed_mps=0.0, localisation=ego_pb2.LOCALISATION_MODE_GNSS_PRECISE, v2x=True,
         gear=vehicle_pb2.GEAR_DRIVE):
    for name in SERVICES:
        manager.set_service_alive(name, True)
    manager.set_localisation_mode(localisation, now_s)
    manager.set_v2x_healthy(v2x, now_s)
    manager.set_vehicle_state(speed_mps, gear, now_s)
    manager.set_control_command_time(now_s)


def test_the_manager_starts_in_manual():
    assert DrivingModeManager(ModesConfig(), COMMAND_TIMEOUT_S).mode == MANUAL


@pytest.mark.parametrize("mode", [COOPERATIVE, AUTONOMOUS])
def test_a_mode_is_granted_when_every_condition_holds(mode):
    manager = ready_manager()
    assert manager.request(mode, 0.0, "driver").accepted
    assert manager.mode == mode
    assert manager.last_change_reason == "requested by driver"


def refused(manager, mode=AUTONOMOUS, now_s=0.0):
    decision = manager.request(mode, now_s)
    assert not decision.accepted
    assert manager.mode == MANUAL
    return decision.unmet


def test_a_dead_service_refuses_the_mode_naming_the_service():
    manager = ready_manager()
    manager.set_service_alive("planner", False)
    unmet = refused(manager)
    assert unmet.reason is Condition.SERVICES_ALIVE
    assert "planner" in str(unmet)


def test_a_service_never_heard_of_counts_as_dead():
    manager = DrivingModeManager(ModesConfig(), COMMAND_TIMEOUT_S)
    feed(manager, 0.0)
    manager._alive.pop("scene")
    assert refused(manager).reason is Condition.SERVICES_ALIVE


def test_degraded_localisation_refuses_autonomous_but_allows_cooperative():
    manager = ready_manager()
    feed(manager, 0.0, localisation=ego_pb2.LOCALISATION_MODE_GNSS_DEGRADED)
    unmet = refused(manager, AUTONOMOUS)
    assert unmet.reason is Condition.LOCALISATION
    assert "GNSS_DEGRADED" in str(unmet)
    assert manager.request(COOPERATIVE, 0.0).accepted


def test_lost_localisation_refuses_cooperative():
    manager = ready_manager()
    feed(manager, 0.0, localisation=ego_pb2.LOCALISATION_MODE_LOST)
    assert refused(manager, COOPERATIVE).reason is Condition.LOCALISATION


def test_unhealthy_v2x_refuses_the_cooperative_modes():
    manager = ready_manager()
    feed(manager, 0.0, v2x=False)
    assert refused(manager, COOPERATIVE).reason is Condition.V2X_HEALTHY
    assert refused(manager, AUTONOMOUS).reason is Condition.V2X_HEALTHY


def test_a_stale_v2x_status_counts_as_unhealthy():
    manager = ready_manager()
    feed(manager, 1.0)
    manager.set_v2x_healthy(True, 0.0)
    assert refused(manager, COOPERATIVE, now_s=1.0).reason is Condition.V2X_HEALTHY


def test_driving_faster_than_10_kmh_refuses_engaging():
    manager = ready_manager(speed_mps=5.0)
    unmet = refused(manager)
    assert unmet.reason is Condition.ENGAGE_SPEED


def test_a_speed_beyond_the_mode_range_refuses_it_even_when_switching_between_automated_modes():
    config = ModesConfig()
    config.autonomous.max_speed_mps = 50.0 / 3.6
    manager = DrivingModeManager(config, COMMAND_TIMEOUT_S)
    feed(manager, 0.0)
    assert manager.request(COOPERATIVE, 0.0).accepted
    feed(manager, 0.1, speed_mps=20.0)
    decision = manager.request(AUTONOMOUS, 0.1)
    assert not decision.accepted
    assert decision.unmet.reason is Condition.SPEED_IN_RANGE
    assert manager.mode == COOPERATIVE


def test_a_gear_other_than_drive_refuses_the_mode():
    manager = ready_manager()
    feed(manager, 0.0, gear=vehicle_pb2.GEAR_NEUTRAL)
    unmet = refused(manager)
    assert unmet.reason is Condition.GEAR and "GEAR_NEUTRAL" in str(unmet)


def test_no_vehicle_state_refuses_the_mode():
    manager = DrivingModeManager(ModesConfig(), COMMAND_TIMEOUT_S)
    assert refused(manager).reason is Condition.VEHICLE_STATE


def test_a_pressed_pedal_refuses_engaging():
    manager = ready_manager()
    manager.set_driver_input("OVERRIDE_REASON_BRAKE at 0.30")
    assert refused(manager).reason is Condition.NO_DRIVER_INPUT


def test_no_fresh_control_command_refuses_the_mode():
    manager = ready_manager()
    feed(manager, 1.0)
    manager.set_control_command_time(0.5)
    assert refused(manager, now_s=1.0).reason is Condition.CONTROL_COMMAND


def test_availability_names_the_unmet_condition_per_mode():
    manager = ready_manager()
    feed(manager, 0.0, localisation=ego_pb2.LOCALISATION_MODE_GNSS_DEGRADED)
    availability = {a.mode: a for a in manager.availability(0.0)}
    assert availability[MANUAL].available
    assert availability[COOPERATIVE].available
    assert not availability[AUTONOMOUS].available
    assert availability[AUTONOMOUS].unmet_condition.startswith(Condition.LOCALISATION.value)


def test_a_condition_lost_while_engaged_forces_a_logged_safe_stop(caplog):
    manager = ready_manager()
    assert manager.request(AUTONOMOUS, 0.0).accepted
    feed(manager, 0.1, localisation=ego_pb2.LOCALISATION_MODE_DEAD_RECKONING)
    with caplog.at_level(logging.WARNING):
        transition = manager.update(0.1)
    assert transition.forced and transition.to_mode == SAFE_STOP
    assert "localisation" in manager.last_change_reason
    assert "forced autonomous -> safe_stop" in caplog.text


def test_autonomous_rides_out_a_short_loss_of_rtk_while_the_estimate_stays_lane_level_but_never_engages_on_it():
    manager = ready_manager()
    assert manager.request(AUTONOMOUS, 0.0).accepted
    feed(manager, 0.1)
    manager.set_localisation_mode(ego_pb2.LOCALISATION_MODE_DEAD_RECKONING, 0.1, position_std_m=0.2)
    assert manager.update(0.1) is None and manager.mode == AUTONOMOUS
    manager.set_localisation_mode(ego_pb2.LOCALISATION_MODE_GNSS_DEGRADED, 0.1, position_std_m=0.6)
    assert manager.update(0.1).to_mode == SAFE_STOP
    fresh = ready_manager()
    fresh.set_localisation_mode(ego_pb2.LOCALISATION_MODE_GNSS_DEGRADED, 0.0, position_std_m=0.1)
    assert refused(fresh).reason is Condition.LOCALISATION


def test_conditions_that_keep_holding_keep_the_mode():
    manager = ready_manager()
    manager.request(COOPERATIVE, 0.0)
    for i in range(1, 10):
        feed(manager, i * 0.05, speed_mps=15.0)
        assert manager.update(i * 0.05) is None
    assert manager.mode == COOPERATIVE


def test_manual_is_always_granted():
    manager = DrivingModeManager(ModesConfig(), COMMAND_TIMEOUT_S)
    assert manager.request(MANUAL, 0.0).accepted


def test_an_unspecified_mode_is_refused():
    manager = ready_manager()
    assert refused(manager, actuation_pb2.DRIVING_MODE_UNSPECIFIED).reason is Condition.KNOWN_MODE
