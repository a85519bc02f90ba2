"""The table of our figures beside the GCDC 2016 papers', made from a sweep's outcomes."""

from coopdrive.launch.batch import BatchSummary, RunOutcome
from coopdrive.launch.paper_figures import PAPER_FIGURES, load_summary, main, paper_table_markdown
from coopdrive.launch.pass_table import pass_table_markdown
from coopdrive.launch.sweep_output import write_summary


def platoon40(seed: int, speed_error_kmh: float, fault: str = "none") -> RunOutcome:
    return RunOutcome("platoon40", seed, True, "", fault=fault,
                      metrics={"speed_error_kmh": speed_error_kmh, "speed_error_rms_kmh": 2 * speed_error_kmh})


def speed_row(table: str) -> str:
    return next(line for line in table.splitlines() if "`speed_error_kmh`" in line)


def test_each_figure_gives_the_mean_over_the_seeds_and_the_worst_seed_beside_the_paper_s():
    row = speed_row(paper_table_markdown(BatchSummary([platoon40(1, 0.05), platoon40(2, 0.08), platoon40(3, 0.05)])))
    cells = [cell.strip() for cell in row.strip("|").split("|")]
    assert cells[1].startswith("0.71 km/h")
    assert cells[3:] == ["3", "0.06 km/h (RMS 0.12 km/h)", "0.08 km/h (seed 2)"]


def test_runs_with_faults_do_not_count_and_figures_no_run_reports_get_no_row():
    table = paper_table_markdown(BatchSummary([platoon40(1, 0.05), platoon40(2, 9.0, fault="loss20")]))
    assert "| 1 | 0.05 km/h" in speed_row(table)
    assert "`lane_change_time_s`" not in table and "`spacing_error_m`" not in table


def test_a_sweep_of_no_scenario_the_papers_measure_has_no_such_table_in_its_pass_table():
    summary = BatchSummary([RunOutcome("follow", 1, True, "", metrics={"speed_error_kmh": 1.0})])
    assert paper_table_markdown(summary) == ""
    assert "GCDC 2016 papers" not in pass_table_markdown(summary)
    assert "GCDC 2016 papers" in pass_table_markdown(BatchSummary([platoon40(1, 0.05)]))


def test_the_command_makes_the_table_from_the_summary_json_a_sweep_wrote(tmp_path, capsys):
    summary = BatchSummary([platoon40(1, 0.05), platoon40(2, 0.07)])
    write_summary(summary, tmp_path)
    assert load_summary(tmp_path / "summary.json").outcomes == summary.outcomes
    main([str(tmp_path / "summary.json")])
    assert capsys.readouterr().out == paper_table_markdown(summary)


def test_the_command_makes_one_table_over_sweeps_of_other_seeds(tmp_path, capsys):
    first, second = BatchSummary([platoon40(1, 0.05)]), BatchSummary([platoon40(2, 0.07), platoon40(3, 0.06)])
    write_summary(first, tmp_path / "seeds-1")
    write_summary(second, tmp_path / "seeds-2-3")
    main([str(tmp_path / "seeds-1" / "summary.json"), str(tmp_path / "seeds-2-3" / "summary.json")])
    table = paper_table_markdown(BatchSummary(first.outcomes + second.outcomes))
    assert capsys.readouterr().out == table
    assert "| 3 | 0.06 km/h" in speed_row(table)


def test_every_figure_names_its_paper_s_lines_and_a_unit():
    assert all(figure.where.split()[0] in ("heudiasyc", "drivertive", "chalmers") and " L" in figure.where
               and figure.unit for figure in PAPER_FIGURES)
