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


def test_a_scenario_that_declares_no_platoon_is_judged_on_none_and_an_unknown_recording_on_the_leading_lane():
    assert catalogue.judging_parameters("merge").platoon == ()
    assert catalogue.judging_parameters("unknown").platoon is None


def test_a_scenario_run_from_its_file_is_judged_with_that_files_judging_section(tmp_path):
    path = tmp_path / "mine.yaml"
    path.write_text(GOOD)
    assert catalogue.judging_parameters(str(path)).headway_s == 1.0
    assert catalogue.judging_parameters(str(tmp_path / "missing.yaml")) == JudgingParameters()


def test_the_shipped_sumo_motorway_is_listed_with_its_network_found_beside_it():
    [entry] = [e for e in catalogue.list_scenarios() if e.name == "sumo-motorway"]
    assert entry.error == "" and "SUMO" in entry.description
