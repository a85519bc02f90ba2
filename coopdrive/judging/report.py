"""A run's report folder: metrics.json, the figures and a one-page index.html that embeds them."""

from __future__ import annotations

import html
import json
from pathlib import Path

from coopdrive.judging.plots import FIGURES, write_figures
from coopdrive.judging.run_messages import RunMessages
from coopdrive.judging.score import JudgingParameters, score_messages, score_series, truth_series
from coopdrive.services.sim.truth_series import TruthSeries
from coopdrive.v1 import sim_pb2

METRICS_FILE = "metrics.json"
INDEX_FILE = "index.html"
# The RunResult's own metrics (the simulator's live judge, sampled every simulation step) go under this key;
# the flat metrics are scored from the recorded ground truth, the same samples `coopdrive score` reads.
LIVE_JUDGE_KEY = "live_judge"


def run_fields(result: sim_pb2.RunResult) -> dict:
    return {"scenario": result.scenario, "seed": result.seed, "success": result.success,
            "failure_reason": result.failure_reason, "sim_time_s": result.sim_time_s,
            "wall_time_s": result.wall_time_s}


def merged_metrics(scored: dict, result: sim_pb2.RunResult | None) -> dict:
    """Run fields, then the scored metrics, then the live judge's metrics as they came in the RunResult."""
    merged = run_fields(result) if result is not None else {}
    merged.update(scored)
    if result is not None:
        merged[LIVE_JUDGE_KEY] = dict(sorted(result.metrics.items()))
    return merged


def _format(value) -> str:
    if isinstance(value, float):
        return f"{value:.3f}"
    return "–" if value is None else str(value)


def _index_html(metrics: dict, figures: list[str]) -> str:
    title = f"coopdrive run {metrics.get('scenario', '')} (seed {metrics.get('seed', '–')})" \
        if "scenario" in metrics else "coopdrive run report"
    rows = "\n".join(f"<tr><td>{html.escape(key)}</td><td>{html.escape(_format(value))}</td></tr>"
                     for key, value in metrics.items() if not isinstance(value, dict))
    live = metrics.get(LIVE_JUDGE_KEY, {})
    live_rows = "\n".join(f"<tr><td>{html.escape(key)}</td><td>{html.escape(_format(value))}</td></tr>"
                          for key, value in live.items())
    if "success" in metrics:
        verdict = "PASS" if metrics["success"] else f"FAIL: {metrics.get('failure_reason', '')}"
        verdict_html = f'<p class="{"pass" if metrics["success"] else "fail"}">{html.escape(verdict)}</p>'
    else:
        verdict_html = ""
    missing = metrics.get("truth_missing_samples") or 0
    if missing:
        verdict_html += (f'<p class="fail">The recording lacks {int(missing)} ground-truth samples (the longest gap '
                         f'{metrics.get("truth_longest_gap_s", 0.0):.1f} s): the figures scored from it are not to '
                         "be trusted; the live judge's are.</p>")
    figures_html = "\n".join(
        f'<figure><img src="{name}" alt="{html.escape(FIGURES[name])}"><figcaption>{html.escape(FIGURES[name])}'
        f"</figcaption></figure>" for name in figures)
    live_html = (f"<h2>Live judge (every simulation step)</h2><table>{live_rows}</table>" if live else "")
    return f"""<!DOCTYPE html>
<html lang="en"><head><meta charset="utf-8"><title>{html.escape(title)}</title>
<style>
body {{ font-family: sans-serif; margin: 1.5em; max-width: 1100px; }}
table {{ border-collapse: collapse; margin-bottom: 1em; }}
td {{ border-bottom: 1px solid #ddd; padding: 2px 12px 2px 0; }}
td:last-child {{ text-align: right; font-family: monospace; }}
.pass {{ color: #176b2c; font-weight: bold; }} .fail {{ color: #a31515; font-weight: bold; }}
.columns {{ display: flex; gap: 2em; flex-wrap: wrap; }}
figure {{ display: inline-block; margin: 0 1em 1em 0; }} img {{ max-width: 520px; }}
</style></head><body>
<h1>{html.escape(title)}</h1>
{verdict_html}
<div class="columns"><div><h2>Scored from ground truth</h2><table>{rows}</table></div><div>{live_html}</div></div>
<h2>Figures</h2>
{figures_html}
<p><a href="{METRICS_FILE}">{METRICS_FILE}</a></p>
</body></html>
"""


def write_report(folder: str | Path, recording_or_series: str | Path | RunMessages | TruthSeries,
                 result: sim_pb2.RunResult | None = None,
                 parameters: JudgingParameters = JudgingParameters()) -> dict:
    """Scores the run (a recording path, collected RunMessages, or a bare TruthSeries) and writes the folder.

    Returns what metrics.json holds. A TruthSeries carries no ego states nor scenes, so its metrics have no
    position_rmse_m nor id_switches.
    """
    folder = Path(folder)
    folder.mkdir(parents=True, exist_ok=True)
    if isinstance(recording_or_series, TruthSeries):
        series = recording_or_series
        scored = score_series(series, parameters)
    else:
        messages = recording_or_series if isinstance(recording_or_series, RunMessages) \
            else RunMessages.from_recording(recording_or_series)
        series = truth_series(messages)
        scored = score_messages(messages, parameters)
    metrics = merged_metrics(scored, result)
    (folder / METRICS_FILE).write_text(json.dumps(metrics, indent=2) + "\n", encoding="utf-8")
    figures = write_figures(series, folder, parameters.standstill_m, parameters.headway_s)
    (folder / INDEX_FILE).write_text(_index_html(metrics, figures), encoding="utf-8")
    return metrics
