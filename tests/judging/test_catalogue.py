from coopdrive.judging import catalogue
from coopdrive.judging.score import JudgingParameters

GOOD = """name: sinus
description: a sinusoid leader
duration_s: 30
vehicles:
  - {vehicle_id: a, station_id: 1, lane: 0, station_m: 0, speed_mps: 10}
judging: {headway_s: 1.0}
"""


def _scenario_folder(monkeypatch, tmp_path, files: dict[str, str]) -> None:
    for name, text in files.items():
        (tmp_path / name).write_text(text)
    monkeypatch.setattr(catalogue.resources, "files", lambda _package: tmp_path)


def test_scenario_files_are_listed_with_their_description_and_nothing_else_is(monkeypatch, tmp_path):
    _scenario_folder(monkeypatch, tmp_path, {"sinus.yaml": GOOD, "notes.txt": "not a scenario"})
    entries = catalogue.list_scenarios()
    assert [(e.name, e.source) for e in entries] == [("sinus", "sinus.yaml")]
    assert entries[0].description == "a sinusoid leader"


def test_a_broken_scenario_file_is_listed_with_its_one_line_error(monkeypatch, tmp_path):
    _scenario_folder(monkeypatch, tmp_path, {"bad.yaml": GOOD.replace("duration_s: 30", "duration_s: -1")})
    bad = [e for e in catalogue.list_scenarios() if e.name == "bad"]
    assert len(bad) == 1 and "duration_s" in bad[0].error and "\n" not in bad[0].error


def test_judging_parameters_come_from_the_scenario_file_of_that_name(monkeypatch, tmp_path):
    _scenario_folder(monkeypatch, tmp_path, {"sinus.yaml": GOOD})
    assert catalogue.judging_parameters("sinus").headway_s == 1.0
    assert catalogue.judging_parameters("unknown") == JudgingParameters()


def test_the_shipped_follow_file_judges_leader_then_ego_at_six_metres_and_one_and_a_half_seconds():
    parameters = catalogue.judging_parameters("follow")
    assert parameters.platoon == ("leader", "ego")
    assert (parameters.standstill_m, parameters.headway_s) == (6.0, 1.5)
