"""CI's bench smoke, second half (tests/foundation/bench_smoke.py): a broken benchmark fails CI; no timing is
asserted."""

import pytest

from tests.foundation.bench_smoke import RUN_TIMEOUT_S, check_smoke_half

pytestmark = pytest.mark.whole_run


@pytest.mark.timeout(RUN_TIMEOUT_S)
def test_each_benchmark_of_the_second_half_measures_finite_figures_into_results_json(tmp_path):
    written = check_smoke_half("second", tmp_path / "results.json")
    gateway = {f["name"]: f["value"] for f in written["benches"]["bench_gateway_ws"]["figures"]}
    assert {"0 clients: sensor -> command p99", "2 clients: sensor -> command p99"} <= set(gateway)
