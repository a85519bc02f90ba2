"""What a stack did about a roadside unit's fault, judged from the truth: stood before the stop line while the fault
was on, crossed without stopping, or was not there; on trajectories whose answers are known in closed form."""

from pathlib import Path

import pytest

from coopdrive.services.sim.fault_config import GnssOutage, SpatLoss
from coopdrive.services.sim.scenario_config import load_scenario
from coopdrive.services.sim.signal_fault_reactions import Reaction, fault_reactions
from tests.sim.signal_truth import AMBER, GREEN, RED, frames, light, steady

SIGNALS = Path(__file__).parents[2] / "scenarios" / "signals.yaml"
# rsu_b's crossroads in the signals scenario.
INTERSECTION_B = 2
GREEN_TILL_40 = light([(GREEN, 0, 40), (AMBER, 40, 43), (RED, 43, 1e9)], INTERSECTION_B)
LOSS = SpatLoss(type="spat_loss", unit_id="rsu_b", start_s=2.0, end_s=13.0)


def stop_and_go(time_s):
    """From 10 m/s, 2 m/s2 braking to stand 2 m before the line at 5 s; off again at 13 s at 2 m/s2, crossing at
    13 + sqrt(2) s."""
    if time_s <= 5.0:
        return -27.0 + 10.0 * time_s - time_s ** 2, 10.0 - 2.0 * time_s
    if time_s <= 13.0:
        return -2.0, 0.0
    return -2.0 + (time_s - 13.0) ** 2, 2.0 * (time_s - 13.0)


@pytest.fixture(scope="module")
def units():
    return load_scenario(SIGNALS).roadside_units


def react(units, trajectory, faults=(LOSS,), light_at=GREEN_TILL_40):
    return fault_reactions(list(faults), units, frames(trajectory, light_at, 20.0), ["car1"])


def test_a_car_standing_before_the_line_while_the_spat_is_lost_stopped_and_its_later_crossing_is_named(units):
    [reaction] = react(units, stop_and_go)
    assert reaction.reaction is Reaction.STOPPED_BEFORE_LINE
    assert reaction.describe() == (
        "spat_loss at rsu_b (2.0-13.0 s): car1 stopped 2.0 m before the stop line of intersection 2 at 4.8 s "
        "(protected movement allowed), crossed at 14.4 s (28.6 s before red)")


def test_a_car_crossing_while_the_spat_is_lost_crossed_without_stopping(units):
    [reaction] = react(units, steady(10.0, 5.0))
    assert reaction.reaction is Reaction.CROSSED
    assert reaction.describe() == ("spat_loss at rsu_b (2.0-13.0 s): car1 crossed the stop line of intersection 2 "
                                   "at 5.0 s without stopping (slowest 10.0 m/s, 38.0 s before red)")


def test_a_car_that_slowed_on_the_approach_and_crossed_after_the_fault_ended_approached_it(units):
    short = SpatLoss(type="spat_loss", unit_id="rsu_b", start_s=0.0, end_s=4.0)
    [reaction] = react(units, stop_and_go, faults=(short,))
    assert reaction.reaction is Reaction.APPROACHED
    assert reaction.describe() == (
        "spat_loss at rsu_b (0.0-4.0 s): car1 on an approach to intersection 2 while the fault lasted, neither "
        "stopping nor crossing (slowest 2.2 m/s), crossed at 14.4 s (28.6 s before red)")


def test_a_car_through_before_the_fault_began_did_not_meet_it(units):
    [reaction] = react(units, steady(10.0, 1.0))
    assert reaction.reaction is Reaction.NOT_MET
    assert reaction.describe().endswith("car1 not on an approach to intersection 2 while the fault lasted")


def test_a_car_standing_at_another_crossroads_did_not_meet_the_fault_of_this_one(units):
    at_the_first = light([(GREEN, 0, 40), (AMBER, 40, 43), (RED, 43, 1e9)], INTERSECTION_B - 1)
    [reaction] = react(units, stop_and_go, light_at=at_the_first)
    assert reaction.reaction is Reaction.NOT_MET


def test_a_fault_of_no_roadside_unit_is_not_judged_here(units):
    outage = GnssOutage(type="gnss_outage", vehicle_id="car1", start_s=2.0)
    assert react(units, stop_and_go, faults=(outage,)) == []
