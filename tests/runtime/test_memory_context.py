"""MemoryContext, the one in-memory ServiceContext of the tests: a service started on it is fed, timed and read
back without a bus."""

import threading

from coopdrive.bus import Envelope
from coopdrive.runtime.service import Service
from coopdrive.runtime.testing import MemoryContext
from coopdrive.v1 import ego_pb2, sim_pb2


class Echo(Service):
    """Republishes each ego state's speed on a period and says who is alive."""

    name = "echo"

    def start(self) -> None:
        self.speeds_mps: list[float] = []
        self.alive: dict[str, bool] = {}
        self.ctx.subscribe("ego/state", self.on_state)
        self.ctx.subscribe("clock", lambda envelope: self.speeds_mps.append(-1.0), vehicle_id="world")
        self.ctx.every(0.1, self.tick)
        self.ctx.watch_liveliness(self.alive.__setitem__)

    def on_state(self, envelope: Envelope) -> None:
        self.speeds_mps.append(envelope.message.speed_mps)

    def tick(self, now_s: float) -> None:
        if self.speeds_mps:
            self.ctx.publish("ego/state", ego_pb2.EgoState(speed_mps=self.speeds_mps[-1]), sample_time_s=now_s - 0.05)


def started(ctx: MemoryContext) -> Echo:
    service = Echo(Echo.Config(), ctx)
    service.start()
    return service


def test_a_delivered_message_reaches_only_the_handlers_subscribed_to_its_vehicle_and_topic():
    ctx = MemoryContext()
    service = started(ctx)
    ctx.deliver("ego/state", ego_pb2.EgoState(speed_mps=3.0))
    ctx.deliver("ego/state", ego_pb2.EgoState(speed_mps=9.0), vehicle_id="leader")
    ctx.deliver("clock", sim_pb2.SimClock(time_s=1.0), vehicle_id="world")
    assert service.speeds_mps == [3.0, -1.0]
    assert ctx.subscriptions() == {("ego", "ego/state"), ("world", "clock")}


def test_advancing_the_clock_runs_the_due_triggers_and_what_they_publish_is_stamped_and_read_back_by_topic():
    ctx = MemoryContext()
    started(ctx)
    ctx.clock.set(2.0)
    ctx.deliver("ego/state", ego_pb2.EgoState(speed_mps=3.0))
    ctx.advance_to(2.0)
    ctx.advance_to(2.05)  # not due yet
    ctx.advance_to(2.1)
    [first, second] = ctx.messages("ego/state")
    assert (first.speed_mps, first.header.sent_time_s, first.header.sample_time_s) == (3.0, 2.0, 1.95)
    assert (second.header.sent_time_s, second.header.sequence, second.header.sender) == (2.1, 2, "test")
    assert ctx.published == [("ego/state", first), ("ego/state", second)]
    assert ctx.messages("ego/state", vehicle_id="leader") == []
    assert ctx.trigger_periods_s() == {"tick": 0.1}


def test_a_message_delivered_without_a_sent_time_gets_the_clock_s_now():
    ctx = MemoryContext()
    started(ctx)
    ctx.clock.set(4.0)
    unstamped, stamped = ego_pb2.EgoState(), ego_pb2.EgoState()
    stamped.header.sent_time_s = 3.5
    ctx.deliver("ego/state", unstamped)
    ctx.deliver("ego/state", stamped)
    assert (unstamped.header.sent_time_s, stamped.header.sent_time_s) == (4.0, 3.5)


def test_liveliness_and_stop_requests_are_passed_on_and_remembered():
    ctx = MemoryContext()
    service = started(ctx)
    ctx.set_alive("ego/planner", True)
    ctx.set_alive("ego/planner", False)
    ctx.request_stop("port taken")
    assert service.alive == {"ego/planner": False}
    assert ctx.stop_reasons == ["port taken"]


def test_queued_calls_from_another_thread_run_on_the_test_s_thread_when_pumped():
    ctx = MemoryContext(queue_calls=True)
    ran_on: list[str] = []
    thread = threading.Thread(target=lambda: ctx.call_soon(lambda: ran_on.append(threading.current_thread().name)))
    thread.start()
    thread.join()
    assert ran_on == []
    ctx.pump(1)
    assert ran_on == [threading.current_thread().name]
