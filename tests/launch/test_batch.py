"""Batch runs (sweeps): seeds parsed as users write them, every (scenario, fault variant, seed) once, a bad pair
refused before anything runs, and the summary files with each run's folder."""

import csv
import io
import json
import pickle
import re
import subprocess
import sys
import time
from contextlib import contextmanager

import pytest
from rich.console import Console

from coopdrive.cli import sweep_exit_status
from coopdrive.exit_status import EXIT_FAILED, EXIT_INCOMPLETE, EXIT_OK
from coopdrive.launch.batch import BatchOptions, BatchSummary, RunOutcome, SweepEnd, parse_seeds, scenario_names
from coopdrive.launch.process_layout import ProcessLayout
from coopdrive.launch.run_spec import RunSpec
from coopdrive.launch.sweep import check_runs, run_batch, sweep_jobs
from coopdrive.launch.sweep_output import retried_lines, summary_table, write_run, write_summary
from coopdrive.launch.sweep_task import run_one
from coopdrive.services.control.longitudinal import CaccLaw
from coopdrive.services.sim.scenario_config import ScenarioError
from coopdrive.services.sim.world_profile import WorldProfile
from coopdrive.v2x.security.profile import SecurityMode
from coopdrive.v1 import sim_pb2

pytestmark = pytest.mark.whole_run

RUN_RESULT = sim_pb2.RunResult(scenario="follow", seed=1, success=True)
LOSSY = ({"type": "v2v_loss", "start_s": 0.0, "loss_probability": 0.3},)


@pytest.mark.parametrize("text, seeds", [("3", [3]), ("1-4", [1, 2, 3, 4]), ("1,4,7-9", [1, 4, 7, 8, 9]),
                                         ("2-3,3", [2, 3])])
def test_seeds_are_single_numbers_ranges_and_lists(text, seeds):
    assert parse_seeds(text) == seeds


@pytest.mark.parametrize("text, named", [("x", "'x'"), ("5-2", "'5-2'"), ("1,,2", "''")])
def test_a_bad_seed_part_is_named(text, named):
    with pytest.raises(ValueError, match=named):
        parse_seeds(text)


def test_all_means_the_built_in_follow_and_every_packaged_scenario():
    names = scenario_names()
    assert {"follow", "string", "merge", "intersection", "emergency"} <= set(names)


def test_a_sweep_runs_every_scenario_fault_variant_and_seed_once():
    jobs = sweep_jobs(BatchOptions(scenarios=["follow", "merge"], seeds=[1, 2, 1], run=RunSpec(duration_s=3.0),
                                   fault_variants={"none": (), "lossy": LOSSY}))
    assert [job.label for job in jobs] == [
        "follow/none/seed-1", "follow/none/seed-2", "follow/lossy/seed-1", "follow/lossy/seed-2",
        "merge/none/seed-1", "merge/none/seed-2", "merge/lossy/seed-1", "merge/lossy/seed-2"]
    assert jobs[2].run.extra_faults == LOSSY and jobs[0].run.extra_faults == () and jobs[0].run.duration_s == 3.0
    assert not jobs[0].report  # a report only where there is an --out to write it to
    with_out = dict(scenarios=["follow"], seeds=[1], out_dir="out")
    assert sweep_jobs(BatchOptions(**with_out))[0].report
    assert not sweep_jobs(BatchOptions(**with_out, reports=False))[0].report


def test_each_run_of_a_sweep_is_the_run_the_sweep_was_given_with_its_scenario_seed_and_faults(monkeypatch):
    given = []
    monkeypatch.setattr("coopdrive.launch.run.run_scenario", lambda options: given.append(options) or RUN_RESULT)
    sweep_run = RunSpec(processes=ProcessLayout.SERVICE, cacc_law=CaccLaw.PLOEG, world=WorldProfile.IDEAL,
                        security=SecurityMode.SIGN_ONLY, stacks=1, duration_s=2.0)
    jobs = sweep_jobs(BatchOptions(scenarios=["merge"], seeds=[4], run=sweep_run, fault_variants={"lossy": LOSSY}))
    job = pickle.loads(pickle.dumps(jobs[0]))  # as a remote Dask worker gets it
    run_one(job, None)
    assert RunSpec(**{name: getattr(given[0], name) for name in RunSpec.model_fields}) == sweep_run.model_copy(
        update={"scenario": "merge", "seed": 4, "extra_faults": LOSSY})
    assert given[0].overrides_of("control") == {"cacc_law": CaccLaw.PLOEG.value}


def test_a_sweep_runs_each_run_in_one_process_unless_told_and_a_single_run_in_one_per_vehicle(monkeypatch):
    """A sweep's runs already fill the cores: one process per run spends less CPU on the same metrics."""
    from coopdrive import cli
    from coopdrive.launch import run, sweep

    swept, single = [], []
    monkeypatch.setattr(sweep, "run_batch", lambda options: swept.append(options.run.processes) or BatchSummary([]))
    monkeypatch.setattr(run, "run_scenario", lambda options: single.append(options.processes) or RUN_RESULT)
    monkeypatch.setattr("coopdrive.launch.summary.print_summary", lambda *args, **kwargs: None)
    cli.main(["run", "follow", "--seeds", "1-2"])
    cli.main(["run", "follow", "--seeds", "1-2", "--processes", "vehicle"])
    cli.main(["run", "follow"])
    assert swept == [ProcessLayout.ONE, ProcessLayout.VEHICLE] and single == [ProcessLayout.VEHICLE]
    assert sweep_jobs(BatchOptions(scenarios=["follow"], seeds=[1]))[0].run.processes is ProcessLayout.ONE


def test_flags_that_only_a_single_run_can_take_stop_a_sweep_in_one_line_naming_them(tmp_path):
    completed = subprocess.run([sys.executable, "-m", "coopdrive.cli", "run", "follow", "--seeds", "1-2", "--realtime",
                                "--record", str(tmp_path / "run.mcap")], capture_output=True, text=True, timeout=60)
    assert completed.returncode == 2
    assert completed.stderr == ("coopdrive: --realtime, --record: for a single run, not a sweep (--out DIR keeps "
                                "each run's report and recording)\n")


def test_flags_that_only_a_sweep_can_take_stop_a_single_run_in_one_line_naming_them(tmp_path):
    completed = subprocess.run([sys.executable, "-m", "coopdrive.cli", "run", "follow", "--out", str(tmp_path),
                                "--no-reports", "--time-limit", "60"], capture_output=True, text=True, timeout=60)
    assert completed.returncode == 2
    assert completed.stderr == ("coopdrive: --out, --no-reports, --time-limit: for a sweep (--seeds or all), not a single run "
                                "(--report DIR writes one run's report)\n")


def test_a_time_limit_that_is_not_above_0_stops_the_sweep_in_one_line():
    completed = subprocess.run([sys.executable, "-m", "coopdrive.cli", "run", "follow", "--seeds", "1-2",
                                "--time-limit", "0"], capture_output=True, text=True, timeout=60)
    assert completed.returncode == 2
    assert completed.stderr == "coopdrive: --time-limit 0: give the seconds the sweep may take (above 0)\n"


def test_a_sweep_s_exit_status_is_4_only_when_its_time_limit_stopped_it_and_no_finished_run_failed():
    passed, failed = RunOutcome("follow", 1, True, ""), RunOutcome("follow", 2, False, "collision")
    left = ["merge/none/seed-1"]
    assert sweep_exit_status(BatchSummary([passed])) == EXIT_OK
    assert sweep_exit_status(BatchSummary([passed], left, SweepEnd.TIME_LIMIT)) == EXIT_INCOMPLETE
    assert sweep_exit_status(BatchSummary([passed, failed], left, SweepEnd.TIME_LIMIT)) == EXIT_FAILED
    assert sweep_exit_status(BatchSummary([passed], left, SweepEnd.INTERRUPTED)) == EXIT_FAILED
    assert sweep_exit_status(BatchSummary([passed, failed])) == EXIT_FAILED


def test_a_sweep_past_its_time_limit_cancels_the_runs_not_finished_names_them_and_exits_4(tmp_path):
    """A minute of follow takes a run over 10 s; the limit is 4 s after the sweep started."""
    out = tmp_path / "sweep"
    completed = subprocess.run([sys.executable, "-m", "coopdrive.cli", "run", "follow", "--seeds", "1-2",
                                "--workers", "1", "--time-limit", "4", "--out", str(out), "--no-reports"],
                               capture_output=True, text=True, timeout=120)
    assert completed.returncode == EXIT_INCOMPLETE, completed.stderr[-2000:]
    assert "time limit of 4 s: 2 run(s) not finished: follow/none/seed-1, follow/none/seed-2" in completed.stdout
    assert json.loads((out / "summary.json").read_text()) == []
    table = (out / "pass_table.md").read_text().splitlines()
    assert table[table.index("Not finished (the sweep's time limit):") + 2:][:2] == [
        "- follow/none/seed-1", "- follow/none/seed-2"]


def test_a_seed_and_a_range_of_seeds_together_stop_the_command_in_one_line():
    completed = subprocess.run([sys.executable, "-m", "coopdrive.cli", "run", "follow", "--seed", "3", "--seeds", "1-2"],
                               capture_output=True, text=True, timeout=60)
    assert completed.returncode == 2
    assert completed.stderr == "coopdrive: --seed 3 and --seeds 1-2: give one of them\n"


def test_a_fault_variant_naming_a_vehicle_the_scenario_lacks_stops_the_sweep_before_anything_runs():
    outage = ({"type": "gnss_outage", "vehicle_id": "a9", "start_s": 5},)
    with pytest.raises(ScenarioError) as raised:
        check_runs(BatchOptions(scenarios=["follow"], seeds=[1], fault_variants={"none": (), "outage": outage}))
    assert str(raised.value) == "fault variant 'outage': follow.yaml: faults.0.vehicle_id: unknown vehicle 'a9'"


def test_each_run_has_its_folder_and_the_summaries_name_the_fault_variant_and_the_retried_runs(tmp_path):
    retried = RunOutcome("follow", 2, True, "", 4.2, {"min_gap_m": 30.0}, fault="lossy", retried=True,
                         lost_workers=["tcp://10.0.0.7:40111"])
    summary = BatchSummary([RunOutcome("follow", 1, True, "", 4.0, {"min_gap_m": 31.0}, fault="lossy"), retried])
    write_run(tmp_path, retried, {"index.html": b"<html>", "figures/gaps.png": b"png"})
    write_summary(summary, tmp_path)
    folder = tmp_path / "follow" / "lossy" / "seed-2"
    assert json.loads((folder / "metrics.json").read_text())["lost_workers"] == ["tcp://10.0.0.7:40111"]
    assert (folder / "report" / "figures" / "gaps.png").read_bytes() == b"png"
    rows = list(csv.DictReader(open(tmp_path / "summary.csv")))
    assert [(row["fault"], row["seed"], row["retried"]) for row in rows] == [("lossy", "1", "False"),
                                                                            ("lossy", "2", "True")]
    assert [row["retried"] for row in json.loads((tmp_path / "summary.json").read_text())] == [False, True]
    console = Console(record=True, width=200)
    console.print(summary_table(summary))
    for line in retried_lines(summary):
        console.print(line)
    printed = console.export_text()
    assert "retried follow/lossy/seed-2 after its worker died: tcp://10.0.0.7:40111" in printed
    assert "| follow | lossy | 2/2 |" in (tmp_path / "pass_table.md").read_text()


def test_a_scenario_given_as_a_file_gets_a_folder_inside_out_named_by_the_file(tmp_path):
    outcome = RunOutcome("/elsewhere/my-test.yaml", 1, True, "")
    write_run(tmp_path / "out", outcome, {})
    assert (tmp_path / "out" / "my-test" / "none" / "seed-1" / "metrics.json").is_file()


def test_a_bad_faults_file_stops_the_command_in_one_line_before_any_cluster_starts(tmp_path):
    faults = tmp_path / "faults.yaml"
    faults.write_text("lossy: [{type: v2v_loss, start_s: -1}]\n")
    completed = subprocess.run([sys.executable, "-m", "coopdrive.cli", "run", "follow", "--seeds", "1-2",
                                "--faults", str(faults)], capture_output=True, text=True, timeout=60)
    assert completed.returncode == 2
    assert completed.stderr == (f"coopdrive: --faults {faults}: variant 'lossy', fault 0: start_s: "
                                "Input should be greater than or equal to 0\n")


def test_the_command_sweeps_on_a_local_cluster_and_writes_the_summaries_and_each_runs_report(tmp_path):
    faults = tmp_path / "faults.yaml"
    faults.write_text("lossy: [{type: v2v_loss, start_s: 0, loss_probability: 0.3}]\n")
    out = tmp_path / "sweep"
    completed = subprocess.run([sys.executable, "-m", "coopdrive.cli", "run", "follow", "--seeds", "1-2",
                                "--workers", "2", "--duration", "3", "--faults", str(faults), "--out", str(out)],
                               capture_output=True, text=True, timeout=240)
    assert completed.returncode == 0, completed.stderr[-2000:]
    # Not a terminal: a line per run as it finishes, then the table as wide as it needs, not cut at 80 columns.
    for seed in (1, 2):
        assert re.search(rf"^[12]/2 follow/lossy/seed-{seed}: pass \(\d+ s\)$", completed.stdout, re.MULTILINE)
    assert "coopdrive batch" in completed.stdout and "│ follow   │ lossy │" in completed.stdout
    assert "rms_jerk_mps3 ┃ first failure ┃" in completed.stdout
    rows = json.loads((out / "summary.json").read_text())
    assert [(row["scenario"], row["fault"], row["seed"], row["success"], row["retried"]) for row in rows] == [
        ("follow", "lossy", 1, True, False), ("follow", "lossy", 2, True, False)]
    for seed in (1, 2):
        folder = out / "follow" / "lossy" / f"seed-{seed}"
        assert json.loads((folder / "metrics.json").read_text())["metrics"] == rows[seed - 1]["metrics"]
        report = json.loads((folder / "report" / "metrics.json").read_text())
        assert report["seed"] == seed and (folder / "report" / "index.html").is_file()
        assert (folder / "report" / "run.mcap").stat().st_size > 0
    assert [row["seed"] for row in csv.DictReader(open(out / "summary.csv"))] == ["1", "2"]
    table = (out / "pass_table.md").read_text()
    assert "| follow | lossy | 2/2 | pass | pass |" in table
    # Every figure column has a value: each is a figure the run's own (live) verdict reports.
    figures_row = next(line for line in table.splitlines()[3:] if line.startswith("| follow | lossy |"))
    assert "-" not in [cell.strip() for cell in figures_row.split("|")[3:-1]], figures_row


def test_a_sweep_s_time_limit_counts_the_time_its_cluster_took_to_start(monkeypatch):
    from coopdrive.launch import sweep_cluster

    cluster_start_s = 0.5
    given_s = []

    @contextmanager
    def slow_cluster(_address, _workers):
        time.sleep(cluster_start_s)
        yield None

    def no_runs(_client, jobs, _on_outcome, time_limit_s):
        given_s.append(time_limit_s)
        return jobs, SweepEnd.TIME_LIMIT

    monkeypatch.setattr(sweep_cluster, "sweep_client", slow_cluster)
    monkeypatch.setattr(sweep_cluster, "stream_runs", no_runs)
    run_batch(BatchOptions(scenarios=["follow"], seeds=[1], time_limit_s=30.0), Console(file=io.StringIO()))
    assert 0 < given_s[0] <= 30.0 - cluster_start_s
    run_batch(BatchOptions(scenarios=["follow"], seeds=[1], time_limit_s=0.2), Console(file=io.StringIO()))
    assert given_s[1] == 0.0
