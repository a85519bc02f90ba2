"""MidRunJoin: a follower restarted after a crash joins the lockstep run at a step the simulator chose."""

from coopdrive.runtime.barrier import StepBarrier
from coopdrive.runtime.rejoin import MidRunJoin

EVERYONE = frozenset({"v/scene", "v/control", "v/actuation"})


def control_barrier() -> StepBarrier:
    barrier = StepBarrier("control")
    barrier.depend_on("v/scene")
    barrier.subscribed.add("v/scene")
    return barrier


def test_a_follower_whose_first_clock_is_step_0_starts_at_step_0_and_sees_nobody_join():
    join = MidRunJoin(control_barrier())
    assert join.on_clock(0, EVERYONE, {}) == frozenset()
    assert join.joined_step == 0


def test_a_follower_whose_first_clock_comes_later_joins_at_the_next_step_with_the_counted_messages_taken_as_sent():
    barrier = control_barrier()
    join = MidRunJoin(barrier)
    join.on_clock(349, EVERYONE, {"v/scene": 70, "v/gnss/fix": 12})
    assert join.joined_step == 350
    # Scene's messages up to 70 went out before this service listened: it does not wait for them.
    assert barrier.holds({"v/scene": 70})
    assert not barrier.holds({"v/scene": 71})


def test_markers_of_steps_before_the_join_set_the_baseline_and_later_ones_are_waited_for():
    barrier = control_barrier()
    join = MidRunJoin(barrier)
    join.on_clock(349, EVERYONE, {})
    join.on_marker("v/scene", 345, 350, {"v/scene": 69})  # re-sent by scene: step 345, quiet until 350
    assert barrier.missing(349, EVERYONE) == []
    join.on_marker("v/scene", 350, 351, {"v/scene": 70})
    assert barrier.missing(350, EVERYONE) == ["v/scene"]  # message 70 of step 350 is still on its way
    barrier.mark_received("v/scene", 70)
    assert barrier.missing(350, EVERYONE) == []


def test_markers_that_arrive_before_the_first_clock_are_judged_by_the_step_it_names():
    barrier = control_barrier()
    join = MidRunJoin(barrier)
    join.on_marker("v/scene", 340, 345, {"v/scene": 68})
    assert barrier.done_step("v/scene") == -1  # not known yet whether it predates the start
    join.on_clock(349, EVERYONE, {})
    assert barrier.done_step("v/scene") == 344 and barrier.holds({"v/scene": 68})


def test_a_clock_listing_a_participant_for_the_first_time_names_it_as_joining():
    join = MidRunJoin(control_barrier())
    join.on_clock(0, EVERYONE, {})
    assert join.on_clock(199, EVERYONE - {"v/control"}, {}) == frozenset()  # a crash: one fewer
    assert join.on_clock(349, EVERYONE, {}) == {"v/control"}
    assert join.on_clock(350, EVERYONE, {}) == frozenset()
