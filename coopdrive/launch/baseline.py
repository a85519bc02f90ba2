"""A run beside a reference: the same scenario and seed again with every stack on a reference CACC law, or the
scenario's platoon under Plexe's controllers in SUMO (coopdrive/launch/plexe_baseline.py).

The string acceptance compares our CACC with the Ploeg CACC at the same time gap (the planner's), so the baseline
changes the control law and nothing else; ours passes only if it damps the speed wave at least as well. Each pair's
string gain is shown beside the largest, which decides.
"""

from __future__ import annotations

from dataclasses import dataclass

from rich.console import Console
from rich.table import Table

from coopdrive.launch.run import RunOptions
from coopdrive.services.control.longitudinal import CaccLaw
from coopdrive.services.sim.string_gain import pair_gain_keys
from coopdrive.v1 import sim_pb2

# Metrics shown side by side, and the one that decides (lower is better).
COMPARED_METRICS = ("string_gain", "min_gap_m", "spacing_error_m", "max_abs_accel_mps2", "rms_jerk_mps3")
DECIDING_METRIC = "string_gain"


def with_cacc_law(options: RunOptions, law: CaccLaw) -> RunOptions:
    """The same run with every stack's cooperative law replaced."""
    return options.model_copy(update={"cacc_law": law})


@dataclass(frozen=True)
class BaselineComparison:
    # The baseline's name (a CACC law, or sumo-plexe) and what it is, for the table's title.
    law: str
    ours: dict[str, float]
    baseline: dict[str, float]
    title: str = ""

    @classmethod
    def of(cls, law: CaccLaw, ours: sim_pb2.RunResult, baseline: sim_pb2.RunResult) -> BaselineComparison:
        return cls(law.value, dict(ours.metrics), dict(baseline.metrics),
                   f"the {law.value} CACC baseline (same scenario, seed and time gap)")

    def compared_metrics(self) -> list[str]:
        """The metrics of the table: the compared ones, then each pair's string gain, leader's pair first."""
        return ([key for key in COMPARED_METRICS if key in self.ours or key in self.baseline]
                + pair_gain_keys({**self.ours, **self.baseline}))

    @property
    def decided(self) -> bool:
        return DECIDING_METRIC in self.ours and DECIDING_METRIC in self.baseline

    @property
    def ours_no_worse(self) -> bool:
        """Ours damps at least as well as the reference; nothing to decide (no string gain) counts as no worse."""
        return not self.decided or self.ours[DECIDING_METRIC] <= self.baseline[DECIDING_METRIC]

    def failure_reason(self) -> str:
        if self.ours_no_worse:
            return ""
        return (f"ours damps worse than the {self.law} baseline: {DECIDING_METRIC} "
                f"{self.ours[DECIDING_METRIC]:.3f} > {self.baseline[DECIDING_METRIC]:.3f}")

    def as_dict(self) -> dict:
        return {"law": self.law, "title": self.title, "ours_no_worse": self.ours_no_worse,
                "metrics": {key: {"ours": self.ours.get(key), "baseline": self.baseline.get(key)}
                            for key in self.compared_metrics()}}

    def print(self, console: Console | None = None) -> None:
        table = Table(title=f"ours beside {self.title}")
        table.add_column("metric")
        table.add_column("ours", justify="right")
        table.add_column(self.law, justify="right")
        for key, values in self.as_dict()["metrics"].items():
            table.add_row(key, *("-" if v is None else f"{v:.3f}" for v in (values["ours"], values["baseline"])))
        console = console or Console()
        console.print(table)
        if self.decided:
            console.print("[bold green]ours damps at least as well[/]" if self.ours_no_worse
                          else f"[bold red]{self.failure_reason()}[/]")
