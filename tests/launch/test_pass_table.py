"""The sweep's pass table: a row per (scenario, fault variant), a column per seed, figures averaged, every failure,
every retried run and every run left unfinished named."""

import pytest

from coopdrive.launch.batch import BatchSummary, RunOutcome, SweepEnd
from coopdrive.launch.pass_table import pass_table_markdown


def test_the_pass_table_marks_each_seed_averages_the_figures_and_names_every_failure_and_retry():
    summary = BatchSummary([
        RunOutcome("merge", 1, True, "", metrics={"spacing_error_m": 0.5, "collisions": 0.0}),
        RunOutcome("merge", 2, False, "merge not completed: a1 still in the closed lane",
                   metrics={"spacing_error_m": 1.5, "collisions": 0.0}),
        RunOutcome("follow", 1, True, "", metrics={"speed_error_kmh": 0.7}),
        RunOutcome("follow", 1, True, "", metrics={"speed_error_kmh": 0.9}, fault="lossy", retried=True,
                   lost_workers=["tcp://10.0.0.7:40111"]),
    ])
    table = pass_table_markdown(summary)
    lines = table.splitlines()
    assert lines[0] == "| scenario | fault | passed | seed 1 | seed 2 |"
    assert "| follow | none | 1/1 | pass |  |" in lines
    assert "| follow | lossy | 1/1 | pass |  |" in lines
    assert "| merge | none | 1/2 | pass | FAIL |" in lines
    merge_figures = next(line for line in lines if line.startswith("| merge | none |") and "1.000" in line)
    assert merge_figures.split(" | ")[3] == "1.000"  # spacing error: mean of 0.5 and 1.5
    assert "- merge/none/seed-2: merge not completed: a1 still in the closed lane" in lines
    assert "- follow/lossy/seed-1: lost tcp://10.0.0.7:40111" in lines


@pytest.mark.parametrize(("metric", "named"), [
    ("lockstep_messages_given_up", "- merge/none/seed-11: 3 times"),  # not deterministic
    ("phantom_brakes", "- merge/none/seed-11: 3"),
])
def test_runs_in_which_lockstep_gave_up_or_that_braked_for_a_phantom_are_named_with_their_count(metric, named):
    summary = BatchSummary([
        RunOutcome("merge", 11, False, "safe stop: b3 at 81.8 s", metrics={metric: 3.0}),
        RunOutcome("merge", 12, True, "", metrics={metric: 0.0}),
    ])
    lines = pass_table_markdown(summary).splitlines()
    assert named in lines
    assert not any(line.startswith("- merge/none/seed-12") for line in lines)


def test_runs_a_time_limit_left_unfinished_are_named_under_why_the_sweep_stopped():
    summary = BatchSummary([RunOutcome("string", 1, True, "")], unfinished=["follow/none/seed-1"],
                           end=SweepEnd.TIME_LIMIT)
    lines = pass_table_markdown(summary).splitlines()
    assert "| string | none | 1/1 | pass |" in lines
    assert lines[lines.index("Not finished (the sweep's time limit):") + 2] == "- follow/none/seed-1"


def test_a_sweep_that_finished_no_run_still_has_a_well_formed_header():
    lines = pass_table_markdown(BatchSummary([], unfinished=["follow/none/seed-1"], end=SweepEnd.TIME_LIMIT))
    assert lines.splitlines()[:2] == ["| scenario | fault | passed |", "|---|---|---|"]
