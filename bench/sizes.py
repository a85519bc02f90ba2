"""How large each benchmark's workload is: its full size, or with COOPDRIVE_BENCH_QUICK=1 the smallest that still
runs every path of it. Quick figures mean nothing; they are for the test that checks `make bench` runs to the end
(tests/foundation/test_benchmarks.py). A benchmark's own environment variables still override both."""

from __future__ import annotations

import os
from typing import TypeVar

QUICK_VARIABLE = "COOPDRIVE_BENCH_QUICK"

Size = TypeVar("Size", int, float)


def sized(full: Size, quick: Size) -> Size:
    return quick if os.environ.get(QUICK_VARIABLE) == "1" else full
