"""The planner service around the state machines: what reaches the bus and the service log."""

import logging

import pytest
from signal_world import GREEN, RED, ego_at, light, mapem

from coopdrive.runtime.testing import MemoryContext
from coopdrive.services.planner.service import PlannerService
from coopdrive.v1 import planner_pb2


def test_each_transition_is_logged_once_with_its_reason(caplog):
    ctx = MemoryContext(log=logging.getLogger("test.planner"))
    service = PlannerService(PlannerService.Config(), ctx)
    service.start()
    with caplog.at_level(logging.INFO, logger="test.planner"):
        service.plan(0.1)
        service.pending_force.append(planner_pb2.PlannerForce(state="SLOW_SAFE", requested_by="alice",
                                                              reason="drill"))
        service.plan(0.2)
        service.plan(0.3)
    logged = [record.getMessage() for record in caplog.records]
    lines = [line for line in logged if line.startswith("emergency:")]
    # Started; forced; and, the emergency vehicle being unheard, straight back to normal in the same step.
    assert len(lines) == len(set(lines)) == 3
    # The traffic lights' machine beside it: started, once.
    assert [line for line in logged if line not in lines] == ["traffic_lights:  -> IDLE at 0.10 s on START: machine started"]
    assert "machine started" in lines[0]
    assert "NORMAL -> SLOW_SAFE" in lines[1] and "forced by alice: drill" in lines[1]
    assert "SLOW_SAFE -> NORMAL" in lines[2] and "no longer heard" in lines[2]


@pytest.mark.parametrize("glosa, state, speed_mps", [(True, "GLOSA", 166.2 / 15.9), (False, "STOP", 13.9)])
def test_the_service_plans_on_the_mapem_and_spatem_it_hears_on_its_clocks_utc(glosa, state, speed_mps):
    # Sim time 0 is 10:00:00 UTC: TimeMarks (seconds of the hour) read as sim seconds.
    config = PlannerService.Config(glosa=glosa, clock_epoch_utc="2016-05-28T10:00:00Z",
                                   logic={"cruise_speed_mps": 13.9})
    ctx = MemoryContext()
    service = PlannerService(config, ctx)
    service.start()
    ctx.advance_to(0.1)
    ctx.deliver("ego/state", ego_at(-180.0))
    ctx.deliver("v2x/mapem", mapem())
    ctx.deliver("v2x/spatem", light((RED, 15.0), (GREEN, 45.0)))
    service.plan(0.1)
    assert ctx.messages("planner/lights")[-1].state == state
    behaviour = ctx.messages("planner/behaviour")[-1]
    assert behaviour.has_stop_line and behaviour.desired_speed_mps == pytest.approx(speed_mps, rel=1e-3)
