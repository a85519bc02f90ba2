"""Machine: what a benchmark run ran on, written into bench/results.json. Absolute figures are compared only
between runs on the same kind of machine (the same CPU model and as many cores to run on); the load at the start
tells how busy it was."""

from __future__ import annotations

import os
import platform
from dataclasses import asdict, dataclass
from pathlib import Path

CPUINFO = Path("/proc/cpuinfo")


@dataclass(frozen=True)
class Machine:
    cpu_model: str
    cores: int
    load_1m_at_start: float
    python: str

    @classmethod
    def now(cls) -> Machine:
        return cls(cpu_model=_cpu_model(), cores=len(os.sched_getaffinity(0)), load_1m_at_start=os.getloadavg()[0],
                   python=platform.python_version())

    def same_kind_as(self, other: Machine) -> bool:
        """Whether absolute figures of the two compare: the same CPU model and cores (the load is not the
        machine's: it is why absolute figures move even on the same machine)."""
        return (self.cpu_model, self.cores) == (other.cpu_model, other.cores)

    def describe(self) -> str:
        return f"{self.cpu_model}, {self.cores} cores, load {self.load_1m_at_start:.1f} at start, Python {self.python}"

    def as_json(self) -> dict:
        return asdict(self)

    @classmethod
    def from_json(cls, row: dict) -> Machine:
        return cls(str(row["cpu_model"]), int(row["cores"]), float(row["load_1m_at_start"]), str(row["python"]))


def _cpu_model() -> str:
    try:
        for line in CPUINFO.read_text().splitlines():
            if line.startswith("model name"):
                return line.split(":", 1)[1].strip()
    except OSError:
        pass
    return platform.processor() or platform.machine()
