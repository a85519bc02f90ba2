"""`coopdrive run` (and so `make run`) tells a short story: a verdict line, what happened, five figures with units,
and where to go next; a progress line on a terminal while it runs."""

import io
from pathlib import Path

from coopdrive.launch.progress_line import ProgressLine
from coopdrive.launch.run_story import KEY_FIGURE_COUNT, key_figures, next_steps, sentences, tell, verdict_line
from coopdrive.launch.summary import summary_dict
from coopdrive.v1 import sim_pb2


def follow_result(success: bool = True) -> sim_pb2.RunResult:
    result = sim_pb2.RunResult(scenario="follow", seed=3, success=success, sim_time_s=60.0, wall_time_s=20.0,
                               failure_reason="" if success else "collision: ego hit leader")
    result.metrics.update({"min_gap_m": 19.9, "min_time_gap_s": 1.79, "spacing_error_m": 3.34,
                           "spacing_error_rms_m": 4.67, "spacing_error_max_m": 12.0, "speed_error_kmh": 2.67,
                           "max_abs_accel_mps2": 2.19, "string_gain": 0.95, "collisions": 0, "hard_brakes": 1})
    return result


def test_the_verdict_line_names_the_run_and_why_it_failed():
    assert verdict_line(summary_dict(follow_result())) == "PASS  follow (seed 3)"
    assert verdict_line(summary_dict(follow_result(False))) == "FAIL  follow (seed 3): collision: ego hit leader"


def test_the_story_says_what_the_scenario_does_how_closely_the_stacks_followed_and_how_safe_it_was():
    told = sentences(summary_dict(follow_result()), "A scripted leader changes speed.")
    assert told[0] == "A scripted leader changes speed."
    assert "within 12.0 m of its spacing policy (4.7 m RMS)" in told[1] and "closer than 19.9 m" in told[1]
    assert told[2].startswith("0 collisions and 1 hard brakes in 60 s simulated")


def test_five_key_figures_are_shown_with_their_units_in_order_of_preference():
    figures = key_figures(summary_dict(follow_result()))
    assert len(figures) == KEY_FIGURE_COUNT
    assert [(figure.metric, figure.unit) for figure, _ in figures][:2] == [("min_gap_m", "m"), ("min_time_gap_s", "s")]


def test_next_steps_name_the_recording_the_replay_and_the_full_table():
    steps = next_steps("follow", Path("out/follow.mcap"), None)
    assert any("out/follow.mcap" in step and "Foxglove" in step for step in steps)
    assert any("coopdrive replay out/follow.mcap --service control" in step for step in steps)
    assert any("--json" in step and "--report" in step for step in steps)
    assert any("index.html" in step for step in next_steps("follow", None, Path("out/r")))


def test_a_run_in_which_lockstep_gave_up_waiting_is_told_as_not_deterministic(capsys):
    result = follow_result()
    result.metrics["lockstep_messages_given_up"] = 3.0
    tell(result)
    assert "not deterministic: 3 times lockstep went on" in capsys.readouterr().out


def test_the_progress_line_draws_only_on_a_terminal_and_clears_itself():
    piped = io.StringIO()
    line = ProgressLine(piped)
    line.update(30.0, 60.0)
    line.close()
    assert piped.getvalue() == ""
