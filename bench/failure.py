"""BenchFailed: a benchmark that could not measure what it says, with a one-line reason (`make bench` prints it
beside the benchmark's name and exits non-zero)."""

from __future__ import annotations


class BenchFailed(Exception):
    pass


def require_success(result, what: str) -> None:
    """A run a figure depends on must have succeeded: its timings would otherwise be those of a run cut short."""
    if not result.success:
        raise BenchFailed(f"{what} failed: {result.failure_reason or 'no reason given'}")
