"""A benchmark's figure (bench/figure.py): a ratio names its baseline and its direction, an absolute figure takes
its direction from its unit, a figure that is not a number survives results.json as not measured, and a
percentile ratio carries its bootstrap interval (bench/percentile_interval.py)."""

import json
import math

import numpy as np
import pytest

from bench.figure import Better, Figure, Unit, ratio, shown
from bench.percentile_interval import percentile_ratio_spread


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


def test_a_p99_ratio_of_a_few_hundred_latencies_has_a_wide_interval_and_a_median_ratio_a_narrower_one():
    rng = np.random.default_rng(3)
    without_clients, with_clients = rng.gamma(2.0, 1.0, 800), rng.gamma(2.0, 1.0, 800)
    p99_spread = percentile_ratio_spread(without_clients, with_clients, 99)
    p50_spread = percentile_ratio_spread(without_clients, with_clients, 50)
    assert 0.10 < p99_spread < 0.40 and 0.02 < p50_spread < p99_spread
    assert percentile_ratio_spread(without_clients, with_clients, 99) == p99_spread  # the same resamples each time


def test_a_figure_s_spread_is_written_and_read_back():
    figure = ratio("50 clients: p99 to 0 clients'", 1.1, "0 clients: sensor -> command p99", Better.LOWER, 0.2)
    assert Figure.from_json(figure.as_json()).spread == 0.2
