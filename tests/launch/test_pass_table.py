"""The sweep's pass table: a row per scenario, a column per seed, figures averaged, every failure named."""

from coopdrive.launch.batch import BatchSummary, RunOutcome
from coopdrive.launch.pass_table import pass_table_markdown


def test_the_pass_table_marks_each_seed_averages_the_figures_and_names_every_failure():
    summary = BatchSummary([
        RunOutcome("merge", 1, True, "", metrics={"spacing_error_m": 0.5, "collisions": 0.0}),
        RunOutcome("merge", 2, False, "merge not completed: a1 still in the closed lane",
                   metrics={"spacing_error_m": 1.5, "collisions": 0.0}),
        RunOutcome("follow", 1, True, "", metrics={"speed_error_kmh": 0.7}),
    ])
    table = pass_table_markdown(summary)
    lines = table.splitlines()
    assert lines[0] == "| scenario | passed | seed 1 | seed 2 |"
    assert "| follow | 1/1 | pass |  |" in lines
    assert "| merge | 1/2 | pass | FAIL |" in lines
    merge_figures = next(line for line in lines if line.startswith("| merge |") and "1.000" in line)
    assert merge_figures.split(" | ")[2] == "1.000"  # spacing error: mean of 0.5 and 1.5
    assert "- merge seed 2: merge not completed: a1 still in the closed lane" in lines
