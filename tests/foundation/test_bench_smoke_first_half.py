"""CI's bench smoke, first half (tests/foundation/bench_smoke.py): a broken benchmark fails CI; no timing is asserted."""

import pytest

from tests.foundation.bench_smoke import RUN_TIMEOUT_S, check_smoke_half

pytestmark = pytest.mark.whole_run


@pytest.mark.timeout(RUN_TIMEOUT_S)
def test_each_benchmark_of_the_first_half_measures_finite_figures_into_results_json(tmp_path):
    check_smoke_half("first", tmp_path / "results.json")
