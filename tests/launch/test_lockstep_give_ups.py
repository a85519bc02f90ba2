"""LockstepGiveUps: the run's result says how often its services went on without a promised message."""

from coopdrive.launch.lockstep_give_ups import LockstepGiveUps
from coopdrive.runtime.barrier import MESSAGES_GIVEN_UP_COUNTER
from coopdrive.v1 import diagnostics_pb2


def diagnostics(count: float) -> diagnostics_pb2.Diagnostics:
    return diagnostics_pb2.Diagnostics(counters={MESSAGES_GIVEN_UP_COUNTER: count, "worker_cpu_s": 2.5})


def test_the_total_is_the_latest_count_of_each_service_summed_over_services():
    give_ups = LockstepGiveUps()
    give_ups.observe("coopdrive/a1/diagnostics/scene", diagnostics(1))
    give_ups.observe("coopdrive/a1/diagnostics/scene", diagnostics(3))
    give_ups.observe("coopdrive/b3/diagnostics/control", diagnostics(2))
    give_ups.observe("coopdrive/world/diagnostics/sim", diagnostics_pb2.Diagnostics())
    assert give_ups.total() == 5


def test_a_late_diagnostics_message_carrying_an_older_count_does_not_lower_the_total():
    give_ups = LockstepGiveUps()
    give_ups.observe("coopdrive/a1/diagnostics/scene", diagnostics(3))
    give_ups.observe("coopdrive/a1/diagnostics/scene", diagnostics(2))
    assert give_ups.total() == 3
