import json
import re
import subprocess
import sys

import pytest

from coopdrive.cli import main
from coopdrive.judging.plots import FIGURES
from coopdrive.judging.report import write_report
from coopdrive.v1 import sim_pb2
from tests.judging.synthetic import write_two_car_recording
from tests.scenario_report import FASTEST_LAYOUT

pytestmark = pytest.mark.whole_run

# A loaded 2-core machine runs the 20 s follow loop in well under this.
RUN_TIMEOUT_S = 240


@pytest.fixture(scope="module")
def follow_report(tmp_path_factory):
    """One `coopdrive run follow --duration 20 --report DIR`: (its JSON summary, the report folder)."""
    folder = tmp_path_factory.mktemp("follow") / "report"
    completed = subprocess.run([sys.executable, "-m", "coopdrive.cli", "run", "follow", "--duration", "20", "--json",
                                "--report", str(folder), *FASTEST_LAYOUT], capture_output=True, text=True,
                                timeout=RUN_TIMEOUT_S)
    assert completed.returncode in (0, 1), completed.stderr
    return json.loads(completed.stdout), folder


def test_a_report_holds_metrics_json_every_figure_and_an_index_that_embeds_them(tmp_path):
    result = sim_pb2.RunResult(scenario="two_cars", seed=3, success=True, sim_time_s=1.0)
    result.metrics["min_gap_m"] = 22.5
    metrics = write_report(tmp_path, write_two_car_recording(tmp_path / "two.mcap"), result)
    on_disk = json.loads((tmp_path / "metrics.json").read_text())
    assert on_disk == metrics
    assert on_disk["min_gap_m"] == pytest.approx(23.0) and on_disk["live_judge"] == {"min_gap_m": 22.5}
    assert on_disk["scenario"] == "two_cars" and on_disk["success"] is True
    index = (tmp_path / "index.html").read_text()
    for name in FIGURES:
        assert (tmp_path / name).stat().st_size > 0
        assert f'src="{name}"' in index
    assert "PASS" in index and "min_gap_m" in index


def test_the_index_page_needs_nothing_from_the_network(tmp_path):
    write_report(tmp_path, write_two_car_recording(tmp_path / "two.mcap"))
    index = (tmp_path / "index.html").read_text()
    assert not re.search(r"(src|href)=\"(https?:)?//", index)


def test_score_prints_the_recordings_metrics_as_json(tmp_path, capsys):
    path = write_two_car_recording(tmp_path / "two.mcap")
    assert main(["score", str(path), "--json"]) == 0
    metrics = json.loads(capsys.readouterr().out)
    assert metrics["min_gap_m"] == pytest.approx(23.0) and metrics["id_switches"] == 1


def test_score_refuses_a_file_that_is_not_a_recording_in_one_line(tmp_path, capsys):
    (tmp_path / "notes.mcap").write_text("not mcap")
    assert main(["score", str(tmp_path / "notes.mcap")]) == 2
    error = capsys.readouterr().err
    assert "notes.mcap" in error and len(error.strip().splitlines()) == 1


def test_scenarios_lists_follow_with_its_description(capsys):
    assert main(["scenarios"]) == 0
    lines = capsys.readouterr().out.splitlines()
    follow = [line for line in lines if line.split()[0] == "follow"]
    assert len(follow) == 1 and "leader" in follow[0]


def test_run_follow_with_a_report_writes_metrics_figures_and_index(follow_report):
    summary, folder = follow_report
    metrics = json.loads((folder / "metrics.json").read_text())
    for key in ("min_gap_m", "collisions", "position_rmse_m", "string_gain", "max_abs_accel_mps2"):
        assert metrics[key] is not None, key
    assert metrics["position_rmse_m"] < 1.0
    assert metrics["truth_samples"] >= 200 and metrics["truth_missing_samples"] == 0
    for name in [*FIGURES, "index.html", "run.mcap"]:
        assert (folder / name).stat().st_size > 0, name
    assert metrics["success"] == summary["success"]


def test_the_report_keeps_the_runs_own_result_unchanged_under_live_judge(follow_report):
    summary, folder = follow_report
    live = json.loads((folder / "metrics.json").read_text())["live_judge"]
    assert summary["min_gap_m"] == pytest.approx(live["min_gap_m"], abs=1e-6)
    assert summary["collisions"] == live["collisions"]


def test_scoring_the_runs_recording_gives_the_metrics_scored_live_from_the_same_truth(follow_report, capsys):
    _, folder = follow_report
    metrics = json.loads((folder / "metrics.json").read_text())
    assert main(["score", str(folder / "run.mcap"), "--json"]) == 0
    scored = json.loads(capsys.readouterr().out)
    assert scored["min_gap_m"] == pytest.approx(metrics["min_gap_m"], abs=1e-6)
    assert scored["collisions"] == metrics["collisions"]
    assert scored["truth_samples"] == metrics["truth_samples"]


def test_the_live_judge_sees_every_step_so_its_minimum_gap_is_at_most_the_sampled_one(follow_report):
    _, folder = follow_report
    metrics = json.loads((folder / "metrics.json").read_text())
    # The 10 Hz truth is a subset of the 50 Hz steps the live judge sees; both measure bumper to bumper.
    assert metrics["live_judge"]["min_gap_m"] <= metrics["min_gap_m"] + 1e-9
    assert metrics["min_gap_m"] - metrics["live_judge"]["min_gap_m"] < 0.1
    assert metrics["live_judge"]["collisions"] == metrics["collisions"]


def test_the_report_page_warns_that_figures_from_a_recording_with_lost_ground_truth_are_not_to_be_trusted(tmp_path):
    from coopdrive.judging.run_messages import RunMessages
    from tests.judging.synthetic import truth_at, two_car_frames

    frames = [truth_at(t, vehicles) for t, vehicles in two_car_frames(steps=60)]
    gapped = RunMessages(truth=[frame for frame in frames if not 1.05 < frame.header.sample_time_s < 4.95])
    write_report(tmp_path / "gapped", gapped)
    write_report(tmp_path / "whole", RunMessages(truth=frames))
    assert "lacks 39 ground-truth samples" in (tmp_path / "gapped" / "index.html").read_text()
    assert "ground-truth samples" not in (tmp_path / "whole" / "index.html").read_text()
