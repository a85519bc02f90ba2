"""`coopdrive analyze string`: the predicted string gain of each following law, beside the measured one.

The prediction is services/control/string_stability.py (the frequency response of V_i / V_i-1 between two
identical consecutive vehicles); the measurement is the string_gain a recorded `string` run scores.
"""

from __future__ import annotations

from dataclasses import dataclass
from pathlib import Path

from rich.console import Console
from rich.table import Table

from coopdrive.services.control.profiles import profile_by_name
from coopdrive.services.control.string_stability import DEFAULT_COMM_DELAY_S, FollowingLaw, analyze, plot

PLOT_FILE = "string_stability.png"
# The GCDC string scenario excites the platoon at 0.2 Hz.
EXCITATION_HZ = 0.2


@dataclass
class StringAnalysisOptions:
    laws: list[FollowingLaw]
    profile: str = "car"
    time_gap_s: float | None = None
    comm_delay_s: float = DEFAULT_COMM_DELAY_S
    recording: Path | None = None
    out_dir: Path | None = None


def analyze_string(options: StringAnalysisOptions, console: Console | None = None) -> dict:
    """Prints the table (and writes the plot with out_dir); returns the figures as a dict."""
    console = console or Console()
    profile = profile_by_name(options.profile)
    results = [analyze(law, profile, options.time_gap_s, options.comm_delay_s) for law in options.laws]
    table = Table(title=f"string stability, {profile.name} profile, V2V delay {options.comm_delay_s:.2f} s")
    for column in ("law", "time gap (s)", "max |V_i/V_i-1|", "at (Hz)", f"at {EXCITATION_HZ} Hz", "string stable"):
        table.add_column(column, justify="right")
    figures: dict = {"predicted": {}}
    for result in results:
        table.add_row(result.law.value, f"{result.time_gap_s:.2f}", f"{result.max_speed_gain:.3f}",
                      f"{result.peak_omega_radps / (2 * 3.141592653589793):.3f}",
                      f"{result.gain_at_hz(EXCITATION_HZ):.3f}", "yes" if result.string_stable else "NO")
        figures["predicted"][result.law.value] = {"max_speed_gain": result.max_speed_gain,
                                                  "gain_at_excitation": result.gain_at_hz(EXCITATION_HZ),
                                                  "time_gap_s": result.time_gap_s}
    console.print(table)
    if options.recording is not None:
        figures["measured_string_gain"] = _measured_gain(options.recording)
        console.print(f"measured string gain in {options.recording}: {figures['measured_string_gain']:.3f}")
    if options.out_dir is not None:
        options.out_dir.mkdir(parents=True, exist_ok=True)
        figures["plot"] = str(plot(results, options.out_dir / PLOT_FILE,
                                   title=f"String stability ({profile.name})"))
        console.print(f"plot: {figures['plot']}")
    return figures


def _measured_gain(recording: Path) -> float:
    from coopdrive.judging.catalogue import judging_parameters
    from coopdrive.judging.run_messages import RunMessages
    from coopdrive.judging.score import ScoreError, score_messages

    messages = RunMessages.from_recording(recording)
    name = messages.result.scenario if messages.result is not None else "string"
    metrics = score_messages(messages, judging_parameters(name))
    if metrics.get("string_gain") is None:
        raise ScoreError(f"{recording}: no string gain: the recording's judging names no platoon")
    return float(metrics["string_gain"])
