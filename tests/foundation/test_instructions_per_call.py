"""bench.instructions_per_call: each workload's counted pass alone, the same count every time, in proportion to
the work."""

import pytest

from bench import instructions_per_call
from bench.callgrind import CallgrindError
from bench.instructions_per_call import per_call
from bench.sizes import QUICK_VARIABLE
from tests.system_packages import needs

# The child imports them by name from the repository's root.
WORKLOADS = "tests.foundation.instruction_workloads:sums"
FAILING_WORKLOADS = "tests.foundation.instruction_workloads:malformed_hex"


@pytest.fixture
def full_size(monkeypatch):
    monkeypatch.delenv(QUICK_VARIABLE, raising=False)


@needs("valgrind")
def test_each_workload_is_counted_alone_the_same_twice_and_four_times_the_work_counts_about_four_times(full_size):
    first, second = per_call(WORKLOADS), per_call(WORKLOADS)
    assert first == second
    assert list(first) == ["sum of 1000", "sum of 4000", "sum of 1000, cold"]
    # Start-up and imports (millions of instructions) are outside the counted passes: a call's count is a sum's.
    assert 3.5 < first["sum of 4000"] / first["sum of 1000"] < 4.5
    assert first["sum of 1000, cold"] > first["sum of 1000"]


@needs("valgrind")
def test_a_workload_that_raises_is_a_callgrind_error_naming_the_exception(full_size):
    with pytest.raises(CallgrindError, match="ValueError: non-hexadecimal number"):
        per_call(FAILING_WORKLOADS)


def test_at_the_quick_size_the_workloads_run_natively_and_nothing_is_counted(monkeypatch):
    monkeypatch.setenv(QUICK_VARIABLE, "1")
    ran = []
    monkeypatch.setattr(instructions_per_call, "run_marked", lambda loads: ran.extend(w.name for w in loads))
    assert per_call(WORKLOADS) is None
    assert ran == ["sum of 1000", "sum of 4000", "sum of 1000, cold"]
