"""Workloads for tests/foundation/test_instructions_per_call.py, in a module of their own: the child process that
callgrind runs imports it, and importing pytest there would cost it tens of seconds under callgrind."""

from itertools import repeat

from bench.instructions_per_call import Workload

CALLS = 20


def sums() -> list[Workload]:
    """Sums of 1,000 and 4,000 ones (the same object: no allocations), and of 1,000 cold."""
    return [Workload("sum of 1000", [lambda: sum(repeat(1, 1000))] * CALLS),
            Workload("sum of 4000", [lambda: sum(repeat(1, 4000))] * CALLS),
            Workload("sum of 1000, cold", [lambda: sum(repeat(1, 1000))] * CALLS, warm=False)]


def malformed_hex() -> list[Workload]:
    return [Workload("a malformed frame", [lambda: bytes.fromhex("zz")])]
