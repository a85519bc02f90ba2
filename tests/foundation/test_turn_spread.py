"""A ratio measured in turns about gets the half-width of the 95 % Student-t interval of its turns' mean
(bench/turn_spread.py), and turns() keeps every turn of every side in the order they were taken."""

import math

import pytest

from bench.turn_about import least_of_turns, turns
from bench.turn_spread import MIN_TURNS, turn_ratio_spread


def test_three_turns_give_the_t_interval_of_their_ratios_mean_over_that_mean():
    # Ratios 1.0, 1.1, 1.2: mean 1.1, standard deviation 0.1, t(0.975, 2) = 4.303.
    spread = turn_ratio_spread([1.0, 2.2, 3.6], [1.0, 2.0, 3.0])
    assert spread == pytest.approx(4.3027 * 0.1 / math.sqrt(3) / 1.1, rel=1e-4)


def test_turns_that_all_give_the_same_ratio_have_no_spread():
    assert turn_ratio_spread([2.0, 4.0, 6.0, 8.0], [1.0, 2.0, 3.0, 4.0]) == 0.0


def test_fewer_turns_than_the_minimum_give_no_interval():
    assert turn_ratio_spread([1.0] * (MIN_TURNS - 1), [1.0] * (MIN_TURNS - 1)) is None


def test_a_turn_that_measured_nothing_gives_no_interval_rather_than_one_from_the_others():
    assert turn_ratio_spread([1.0, 1.1, 1.2, 1.3], [1.0, 1.0, 0.0, 1.0]) is None


def test_unequal_numbers_of_turns_are_refused_naming_both():
    with pytest.raises(ValueError, match="3 numerators for 2 denominators"):
        turn_ratio_spread([1.0, 1.0, 1.0], [1.0, 1.0])


def test_turns_keeps_each_sides_measurements_in_the_order_the_sides_took_turns():
    taken = []

    def side(name: str, values: list[float]):
        def measure() -> float:
            taken.append(name)
            return values.pop(0)
        return measure

    measured = turns([side("a", [3.0, 1.0, 2.0]), side("b", [5.0, 6.0, 4.0])], 3)
    assert measured == [[3.0, 1.0, 2.0], [5.0, 6.0, 4.0]]
    assert taken == ["a", "b"] * 3


def test_least_of_turns_is_each_sides_least_turn():
    values = {"a": [3.0, 1.0, 2.0], "b": [5.0, 6.0, 4.0]}
    assert least_of_turns([lambda: values["a"].pop(0), lambda: values["b"].pop(0)], 3) == [1.0, 4.0]
