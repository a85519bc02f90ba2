"""The planner service around the state machines: what reaches the bus and the service log."""

import logging

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
