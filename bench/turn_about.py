"""Both sides of a ratio measured turn about, on this process's CPU clock.

A ratio's sides measured one after the other drift apart when the shared machine's load comes and goes between
them: two `make bench` runs of the same code flagged 17 of 41 ratios that way (docs/performance.md). Measured in
short turns, side A then side B then A again, a busy spell weighs on both alike; the best turn of each side is
kept (timeit's advice: the slower turns measure the machine's other work). Times are this process's CPU time,
which does not count the time the scheduler gave to other processes.
"""

from __future__ import annotations

import time
from collections.abc import Callable, Sequence

# Operations between two reads of the clock: enough that reading it costs nothing beside them.
DEFAULT_BATCH = 20


def cpu_seconds(work: Callable[[], object]) -> float:
    """This process's CPU seconds that one call of work took."""
    start = time.process_time()
    work()
    return time.process_time() - start


def turns(sides: Sequence[Callable[[], float]], rounds: int) -> list[list[float]]:
    """Each side's measurement in each of `rounds` rounds, the sides taking turns within each round: [side][round].
    A side is a callable that does its work and returns what it measured (seconds, us per call...)."""
    measured: list[list[float]] = [[] for _ in sides]
    for _ in range(rounds):
        for index, side in enumerate(sides):
            measured[index].append(side())
    return measured


def least_of_turns(sides: Sequence[Callable[[], float]], rounds: int) -> list[float]:
    """Each side's least measurement over `rounds` turns (turns())."""
    return [min(side) for side in turns(sides, rounds)]


def rate_per_s(operation: Callable[[], object], seconds: float, batch: int = DEFAULT_BATCH) -> float:
    """Operations per CPU second of this process over about `seconds` of it."""
    count, start = 0, time.process_time()
    while True:
        for _ in range(batch):
            operation()
        count += batch
        now = time.process_time()
        if now >= start + seconds:
            return count / (now - start)


def seconds_per_call_in_turns(operations: Sequence[Callable[[], object]], seconds: float, rounds: int,
                              batch: int = DEFAULT_BATCH) -> list[list[float]]:
    """Each operation's CPU seconds per call in each of `rounds` turns of seconds / rounds each: [operation][round]."""
    for operation in operations:
        operation()  # the first call fills caches (schemas, certificates) that later calls find ready
    return turns([lambda op=op: 1.0 / rate_per_s(op, seconds / rounds, batch) for op in operations], rounds)


def best_rates_per_s(operations: Sequence[Callable[[], object]], seconds: float, rounds: int,
                     batch: int = DEFAULT_BATCH) -> list[float]:
    """Each operation's best rate per CPU second over `rounds` turns of seconds / rounds each."""
    return [1.0 / min(each) for each in seconds_per_call_in_turns(operations, seconds, rounds, batch)]
