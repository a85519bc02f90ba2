"""The signal controller: each group's aspect and phase end times at any instant of a fixed-time plan, the
clearance between stages, and an actuated stage's green held for a vehicle and no longer than allowed."""

import pytest
from pydantic import ValidationError

from coopdrive.services.sim.signal_controller import SignalAspect, SignalController
from coopdrive.services.sim.signal_plan import SignalPlan, SignalStage

STEP_S = 0.1


def two_stage_plan(**changes) -> SignalPlan:
    """Groups 1 and 2 green 20 s, then group 3 green 10 s; amber 3 s, all red 2 s (red-amber 1 s): cycle 40 s."""
    fields = dict(stages=[SignalStage(groups=[1, 2], green_s=20.0), SignalStage(groups=[3], green_s=10.0)],
                  amber_s=3.0, all_red_s=2.0, red_amber_s=1.0)
    return SignalPlan(**{**fields, **changes})


def test_a_two_stage_plan_cycles_through_both_stages_with_their_intergreens():
    assert two_stage_plan().cycle_s == pytest.approx(40.0)


@pytest.mark.parametrize("time_s, aspect", [
    (0.0, SignalAspect.GREEN), (19.9, SignalAspect.GREEN), (20.0, SignalAspect.AMBER), (22.9, SignalAspect.AMBER),
    (23.0, SignalAspect.RED), (38.9, SignalAspect.RED), (39.0, SignalAspect.RED_AMBER), (40.0, SignalAspect.GREEN),
    (105.0, SignalAspect.RED)])
def test_the_first_stages_group_shows_green_amber_red_and_red_amber_at_their_times(time_s, aspect):
    assert SignalController(two_stage_plan()).aspect(1, time_s) is aspect


@pytest.mark.parametrize("time_s, aspect", [
    (0.0, SignalAspect.RED), (23.9, SignalAspect.RED), (24.0, SignalAspect.RED_AMBER), (25.0, SignalAspect.GREEN),
    (35.0, SignalAspect.AMBER), (38.0, SignalAspect.RED)])
def test_the_second_stages_group_goes_green_only_after_the_all_red_clearance(time_s, aspect):
    assert SignalController(two_stage_plan()).aspect(3, time_s) is aspect


def test_no_instant_has_two_stages_green_or_amber_at_once():
    controller = SignalController(two_stage_plan())
    moving = (SignalAspect.GREEN, SignalAspect.AMBER)
    for tenth in range(800):
        time_s = tenth * STEP_S
        assert not (controller.aspect(1, time_s) in moving and controller.aspect(3, time_s) in moving), time_s


def test_a_fixed_time_green_states_when_it_ends_and_the_phases_after_it_with_min_max_and_likely_equal():
    phases = SignalController(two_stage_plan()).phases(1, 12.0)
    assert [p.aspect for p in phases] == [SignalAspect.GREEN, SignalAspect.AMBER, SignalAspect.RED,
                                          SignalAspect.RED_AMBER]
    assert [p.min_end_s for p in phases] == pytest.approx([20.0, 23.0, 39.0, 40.0])
    assert all(p.min_end_s == p.max_end_s == p.likely_end_s for p in phases)


def test_the_offset_shifts_the_cycle_so_a_corridor_can_be_coordinated():
    controller = SignalController(two_stage_plan(offset_s=15.0))
    assert controller.aspect(1, 14.0) is SignalAspect.RED_AMBER
    assert controller.phases(1, 15.5)[0].min_end_s == pytest.approx(35.0)


def test_the_end_of_amber_is_the_next_red_and_now_when_red():
    controller = SignalController(two_stage_plan())
    assert (controller.next_red_s(1, 5.0), controller.next_red_s(1, 21.0), controller.next_red_s(1, 30.0)) == \
        (pytest.approx(23.0), pytest.approx(23.0), 30.0)


def actuated() -> SignalController:
    return SignalController(two_stage_plan(stages=[SignalStage(groups=[1], green_s=20.0, max_extension_s=5.0),
                                                   SignalStage(groups=[3], green_s=10.0)]))


def run(controller: SignalController, until_s: float, calling=()) -> None:
    steps = round((until_s - controller.time_s) / STEP_S)
    for k in range(1, steps + 1):
        controller.step(controller.time_s + STEP_S if k < steps else until_s, calling)


def test_an_actuated_green_is_held_while_a_vehicle_calls_and_states_how_much_longer_it_may_last():
    controller = actuated()
    run(controller, 19.0)
    green = controller.phases(1, 19.0)[0]
    assert (green.min_end_s, green.max_end_s, green.likely_end_s) == \
        (pytest.approx(20.0), pytest.approx(25.0), pytest.approx(20.0))
    run(controller, 22.0, calling={1})
    assert controller.aspect(1, 22.0) is SignalAspect.GREEN
    green = controller.phases(1, 22.0)[0]
    assert green.max_end_s == pytest.approx(25.0, abs=STEP_S)
    # Held at its green's end: group 3's red lasts the intergreen and red-amber from now at least.
    assert controller.phases(3, 22.0)[0].min_end_s == pytest.approx(26.0, abs=2 * STEP_S)


def test_an_actuated_green_ends_at_its_longest_extension_however_long_vehicles_call():
    controller = actuated()
    run(controller, 30.0, calling={1})
    assert controller.held_s == pytest.approx(5.0)
    assert controller.aspect(1, 30.0) is SignalAspect.RED


def test_a_fixed_time_plan_ignores_calls():
    controller = SignalController(two_stage_plan())
    run(controller, 25.0, calling={1, 2, 3})
    assert controller.held_s == 0.0 and controller.aspect(1, 25.0) is SignalAspect.RED


def test_a_group_in_two_stages_is_refused_with_the_key_named():
    with pytest.raises(ValidationError, match="one stage only"):
        two_stage_plan(stages=[SignalStage(groups=[1], green_s=5), SignalStage(groups=[1], green_s=5)])


def test_a_red_amber_longer_than_the_clearance_is_refused():
    with pytest.raises(ValidationError, match="red_amber_s"):
        two_stage_plan(red_amber_s=3.0)


def test_asking_for_a_group_the_plan_does_not_have_names_the_groups_it_has():
    with pytest.raises(KeyError, match=r"groups \[1, 2, 3\]"):
        SignalController(two_stage_plan()).phases(9, 0.0)
