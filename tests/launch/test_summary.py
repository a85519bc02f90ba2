import json

from coopdrive.launch.summary import print_summary, summary_dict
from coopdrive.v1 import sim_pb2


def test_event_counts_are_integers_and_measurements_keep_their_decimals():
    result = sim_pb2.RunResult(scenario="intersection", seed=1, success=True, sim_time_s=75.0, wall_time_s=15.0)
    result.metrics["safety_circle_violations"] = 2.0
    result.metrics["automation_lost"] = 0.0
    result.metrics["crossing_time_s"] = 22.7000000001
    summary = summary_dict(result)
    assert json.dumps({k: summary[k] for k in ("safety_circle_violations", "automation_lost", "crossing_time_s")}) \
        == '{"safety_circle_violations": 2, "automation_lost": 0, "crossing_time_s": 22.7}'
    assert summary["realtime_factor"] == 5.0
    # A run that measured no gap still says so in the field scripts read.
    assert summary["min_gap_m"] == -1.0 and summary["collisions"] == 0


def test_the_summary_says_start_up_and_shut_down_apart_from_the_stepping():
    result = sim_pb2.RunResult(scenario="follow", seed=1, success=True, sim_time_s=60.0, wall_time_s=3.0,
                               startup_time_s=1.2345, shutdown_time_s=0.25)
    summary = summary_dict(result)
    assert (summary["wall_time_s"], summary["startup_time_s"], summary["shutdown_time_s"]) == (3.0, 1.234, 0.25)
    assert summary["realtime_factor"] == 20.0


def test_a_run_in_which_lockstep_gave_up_waiting_is_printed_as_not_deterministic(capsys):
    result = sim_pb2.RunResult(scenario="merge", seed=11, success=True, sim_time_s=90.0, wall_time_s=150.0)
    result.metrics["lockstep_messages_given_up"] = 3.0
    print_summary(result)
    assert "not deterministic: 3 times lockstep went on" in capsys.readouterr().out
    result.metrics["lockstep_messages_given_up"] = 0.0
    print_summary(result)
    assert "not deterministic" not in capsys.readouterr().out
