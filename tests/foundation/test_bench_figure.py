"""A benchmark's figure (bench/figure.py): a ratio names its baseline and its direction, an absolute figure takes
its direction from its unit, and a figure that is not a number survives results.json as not measured."""

import json
import math

import pytest

from bench.figure import Better, Figure, Unit, ratio, shown


def test_a_ratio_must_name_its_baseline_and_its_direction_and_only_a_ratio_names_a_baseline():
    with pytest.raises(ValueError, match="a ratio, and only a ratio, names its baseline"):
        Figure("typed p50 to raw", 1.2, Unit.RATIO)
    with pytest.raises(ValueError, match="a ratio, and only a ratio, names its baseline"):
        Figure("typed p50", 120.0, Unit.US, baseline="raw p50")
    with pytest.raises(ValueError, match="says whether lower or higher is better"):
        Figure("typed p50 to raw", 1.2, Unit.RATIO, baseline="raw p50")
    assert ratio("speed-up", 3.0, "general path", Better.HIGHER).is_ratio


def test_an_absolute_figure_is_better_lower_for_costs_and_higher_for_rates_and_real_time_factors():
    assert Figure("p99", 5.0, Unit.MS).better is Better.LOWER
    assert Figure("decodes", 5000.0, Unit.PER_S).better is Better.HIGHER
    assert Figure("8 stacks", 0.6, Unit.REALTIME_FACTOR).better is Better.HIGHER


def test_a_figure_that_is_not_a_number_is_written_as_null_and_read_back_as_not_measured():
    figure = Figure("0 clients: p99", math.nan, Unit.MS)
    row = json.loads(json.dumps(figure.as_json()))
    assert row["value"] is None and not figure.measured
    assert not Figure.from_json(row).measured
    kept = ratio("p99 to 0 clients'", 1.25, "0 clients: p99")
    assert Figure.from_json(json.loads(json.dumps(kept.as_json()))) == kept


def test_values_are_shown_to_about_three_significant_digits_without_exponents():
    assert [shown(v) for v in (0.01234, 1.234, 12.34, 1234.5, 123456.0)] == ["0.0123", "1.23", "12.3", "1,234",
                                                                               "123,456"]
