"""Batch runs: seeds parsed as users write them, runs in parallel workers, a table and summary files."""

import csv
import json

import pytest
from rich.console import Console

from coopdrive.launch.batch import BatchOptions, parse_seeds, run_batch, scenario_names


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


def test_a_batch_runs_each_seed_once_in_parallel_and_the_same_seed_gives_the_same_metrics(tmp_path):
    console = Console(record=True, width=200)
    summary = run_batch(BatchOptions(scenarios=["follow"], seeds=[1, 2, 1], workers=2, out_dir=tmp_path,
                                     duration_s=3.0), console)
    assert sorted(o.seed for o in summary.outcomes) == [1, 2]  # a seed asked twice runs once
    first = json.loads((tmp_path / "follow" / "seed-1" / "metrics.json").read_text())
    assert first["scenario"] == "follow" and "min_gap_m" in first["metrics"]
    again = run_batch(BatchOptions(scenarios=["follow"], seeds=[1], workers=1, duration_s=3.0), console)
    assert again.outcomes[0].metrics == first["metrics"]
    rows = list(csv.DictReader(open(tmp_path / "summary.csv")))
    assert [row["seed"] for row in rows] == ["1", "2"]
    assert "| follow | 2/2 | pass | pass |" in (tmp_path / "pass_table.md").read_text()
    printed = console.export_text()
    assert "coopdrive batch" in printed and "pass rate" in printed and "follow" in printed
