"""HandlerLedger: the CPU each of a service's handlers spends in a run, per topic it handles and per timer it runs.

Set COOPDRIVE_HANDLER_CPU_DIR and every service, in every process of a run, writes
<dir>/<vehicle>-<service>.handlers.csv when it stops; `python -m bench.profile_handlers DIR` adds them up
(docs/performance.md). Each handler call reads its thread's CPU clock before and after, and a handler that runs
another's (a message handed on within the call) is charged only for its own part. A profiler reads a clock at every
function call and return: cProfile on the CPU clock slows a run fourfold and inflates code made of many small calls
most, and a sampling profiler's shares are good to several per cent. Two clock reads per handler call keep the
run at its pace, so these figures are the run's own. What no handler holds (taking events off the queue and
decoding their messages, the lockstep barrier, sending a step's messages with its marker) is the worker's CPU,
the `worker` row, less the handlers' sum.
"""

from __future__ import annotations

import csv
import functools
import logging
import os
import threading
import time
from dataclasses import dataclass
from pathlib import Path
from typing import Callable

log = logging.getLogger(__name__)

HANDLER_CPU_DIR_VARIABLE = "COOPDRIVE_HANDLER_CPU_DIR"
HANDLER_CPU_SUFFIX = ".handlers.csv"
CSV_COLUMNS = ("kind", "name", "calls", "cpu_s", "longest_call_cpu_s")
WORKER_ROW = "worker"

# Per thread, the CPU that the calls nested in each open handler call have spent, innermost last.
_open_calls = threading.local()


@dataclass
class HandlerCost:
    kind: str
    name: str
    calls: int = 0
    cpu_s: float = 0.0
    # The most CPU one call took: a realtime step's latency has its longest handler in it.
    longest_call_cpu_s: float = 0.0


class HandlerLedger:
    def __init__(self, out_file: Path):
        self.out_file = out_file
        self.costs: dict[tuple[str, str], HandlerCost] = {}

    @classmethod
    def from_environment(cls, participant: str) -> HandlerLedger | None:
        """The ledger of a service named `participant` (<vehicle>-<service>), or None when the variable is unset."""
        folder = os.environ.get(HANDLER_CPU_DIR_VARIABLE)
        return cls(Path(folder) / f"{participant}{HANDLER_CPU_SUFFIX}") if folder else None

    def timed(self, kind: str, name: str, handler: Callable) -> Callable:
        """handler, its calls counted and their CPU charged to (kind, name): "topic" and the topic, "timer" or
        "call" (ctx.call_soon) and the handler's name. Several handlers of one name share a row. The handler keeps
        its name: a timer's overruns and failures are reported under it."""
        cost = self.costs.setdefault((kind, name), HandlerCost(kind, name))

        @functools.wraps(handler)
        def charged(*args, **kwargs):
            nested = _open_calls.__dict__.setdefault("nested_cpu_s", [])
            nested.append(0.0)
            started_s = time.thread_time()
            try:
                return handler(*args, **kwargs)
            finally:
                spent_s = time.thread_time() - started_s
                own_s = spent_s - nested.pop()
                if nested:
                    nested[-1] += spent_s
                cost.calls += 1
                cost.cpu_s += own_s
                cost.longest_call_cpu_s = max(cost.longest_call_cpu_s, own_s)

        return charged

    def write(self, worker_cpu_s: float) -> None:
        """The rows, most CPU first, and the worker's own CPU, which holds them and what the runtime spent. A
        folder that cannot be written is named in a warning: a measurement is no reason to fail a service's stop."""
        try:
            self.out_file.parent.mkdir(parents=True, exist_ok=True)
            with self.out_file.open("w", newline="") as out:
                writer = csv.writer(out)
                writer.writerow(CSV_COLUMNS)
                for cost in sorted(self.costs.values(), key=lambda c: -c.cpu_s):
                    writer.writerow((cost.kind, cost.name, cost.calls, f"{cost.cpu_s:.6f}",
                                     f"{cost.longest_call_cpu_s:.6f}"))
                writer.writerow((WORKER_ROW, WORKER_ROW, "", f"{worker_cpu_s:.6f}", ""))
        except OSError as error:
            log.warning("%s=%s: the handlers' CPU could not be written: %s", HANDLER_CPU_DIR_VARIABLE,
                        self.out_file.parent, error)


def handler_name(handler: Callable) -> str:
    """A timer's or a call_soon's row: the function's qualified name (a partial's function's; a lambda's, which
    names the function it was written in)."""
    function = getattr(handler, "func", handler)
    return getattr(function, "__qualname__", type(function).__name__)
