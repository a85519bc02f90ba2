"""service_crash faults as the clock master's outages, and how the judge takes the crashed car's safe stop."""

import pytest
from pydantic import TypeAdapter

from coopdrive.runtime.master import Outage
from coopdrive.services.sim.fault_config import Fault
from coopdrive.services.sim.mission_verdict import MissionJudge
from coopdrive.services.sim.service_crashes import crash_outages, crashed_participants
from coopdrive.v1 import actuation_pb2
from tests.sim.test_mission_verdict import config, truth

RUNNING = ["p1/control", "p1/actuation"]


def faults(*texts):
    return [TypeAdapter(Fault).validate_python(text) for text in texts]


def test_a_crash_with_an_end_restarts_at_the_step_of_its_end():
    crashes = faults({"type": "service_crash", "vehicle_id": "p1", "service": "control", "start_s": 4, "end_s": 7})
    assert crash_outages(crashes, RUNNING, 0.02) == [Outage("p1/control", 200, 350)]
    assert crashed_participants(crashes) == {"p1/control"}


def test_a_crash_without_an_end_restarts_after_composes_first_back_off():
    crashes = faults({"type": "service_crash", "vehicle_id": "p1", "service": "control", "start_s": 4})
    assert crash_outages(crashes, RUNNING, 0.02) == [Outage("p1/control", 200, 205)]


def test_a_crash_of_a_service_that_does_not_run_is_left_out_with_a_warning(caplog):
    crashes = faults({"type": "service_crash", "vehicle_id": "leader", "service": "control", "start_s": 4},
                     {"type": "gnss_outage", "vehicle_id": "p1", "start_s": 1})
    assert crash_outages(crashes, RUNNING, 0.02) == []
    assert "leader/control" in caplog.text


def crash_judge():
    crash = [{"type": "service_crash", "vehicle_id": "a", "service": "control", "start_s": 4, "end_s": 7}]
    judge = MissionJudge(config("follow", faults=crash), ["a", "b"])
    judge.observe(0.0, truth({"vehicle_id": "a", "x_m": 0}, {"vehicle_id": "b", "x_m": 20}))
    for vehicle_id in ("a", "b"):
        judge.observe_automation(vehicle_id, True, 0.1)
        judge.observe_mode(vehicle_id, actuation_pb2.DRIVING_MODE_AUTONOMOUS, 0.1)
    return judge


def test_the_judge_reports_how_long_after_the_crash_the_crashed_car_began_its_safe_stop():
    judge = crash_judge()
    judge.observe_mode("a", actuation_pb2.DRIVING_MODE_SAFE_STOP, 4.02)
    judge.observe_mode("a", actuation_pb2.DRIVING_MODE_SAFE_STOP, 4.04)
    assert judge.metrics()["crash_to_safe_stop_s"] == pytest.approx(0.02)


def test_the_crashed_car_handed_to_its_driver_passes_but_another_car_or_an_earlier_loss_fails():
    judge = crash_judge()
    judge.observe_automation("a", False, 9.0)
    assert judge.verdict() == (True, "")
    judge.observe_automation("b", False, 9.5)
    assert judge.verdict() == (False, "automation lost: b at 9.5 s")
