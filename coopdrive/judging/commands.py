"""What the `coopdrive run --report`, `score` and `scenarios` commands do, behind cli.py's wiring."""

from __future__ import annotations

import json
import sys
from pathlib import Path

from rich.console import Console
from rich.table import Table

from coopdrive.exit_status import EXIT_OK, EXIT_USAGE
from coopdrive.judging.catalogue import judging_parameters, list_scenarios
from coopdrive.judging.run_messages import RunMessages
from coopdrive.judging.score import ScoreError, score_messages
from coopdrive.recording.reader import RecordingError
from coopdrive.v1 import sim_pb2

RECORDING_FILE = "run.mcap"


def run_with_report(options, report_dir: Path) -> sim_pb2.RunResult:
    """Runs with a recording (report_dir/run.mcap unless options.record says where) and writes the report.

    The report is scored from the messages the recording takes, as they are written (so it is what scoring the
    recording afterwards gives); the run's own RunResult (and so its success) is returned unchanged.
    """
    from coopdrive.judging.report import write_report  # matplotlib: only a command that writes a report loads it
    from coopdrive.launch.run import run_scenario

    report_dir = Path(report_dir)
    report_dir.mkdir(parents=True, exist_ok=True)
    messages = RunMessages()
    # From the recording's thread, not Zenoh's: a report of a big run on a loaded host must not hold the stacks back.
    options = options.model_copy(update={"record": options.record or report_dir / RECORDING_FILE,
                                         "on_recorded": messages.add})
    result = run_scenario(options)
    try:
        write_report(report_dir, messages, result, judging_parameters(options.scenario))
    except ScoreError as error:
        print(f"coopdrive: no report: {error}", file=sys.stderr)
    return result


def report_notice(report_dir: Path) -> None:
    from coopdrive.judging.report import INDEX_FILE
    print(f"report: {Path(report_dir) / INDEX_FILE}", file=sys.stderr)


def score_command(path: Path, as_json: bool, scenario: str | None = None) -> int:
    """Prints the metrics of a recording, judged with the scenario's judging section (named by --scenario or
    by the recorded world/result)."""
    try:
        messages = RunMessages.from_recording(path)
        name = scenario or (messages.result.scenario if messages.result is not None else "")
        metrics = score_messages(messages, judging_parameters(name))
    except (ScoreError, OSError) as error:
        print(f"coopdrive: {path}: {error}", file=sys.stderr)
        return EXIT_USAGE
    except RecordingError as error:
        print(f"coopdrive: {error}", file=sys.stderr)
        return EXIT_USAGE
    except Exception as error:  # a damaged or foreign file: one line, not a traceback
        print(f"coopdrive: {path}: cannot read the recording: {error}", file=sys.stderr)
        return EXIT_USAGE
    if as_json:
        print(json.dumps(metrics, indent=2))
        return EXIT_OK
    table = Table(title=f"coopdrive score {path}")
    table.add_column("metric")
    table.add_column("value", justify="right")
    for key, value in metrics.items():
        table.add_row(key, "–" if value is None else f"{value:.3f}" if isinstance(value, float) else str(value))
    Console().print(table)
    return EXIT_OK


def scenarios_command() -> int:
    for entry in list_scenarios():
        text = entry.description if not entry.error else f"(cannot load: {entry.error})"
        print(f"{entry.name:<20} {text}  [{entry.source}]")
    return EXIT_OK
