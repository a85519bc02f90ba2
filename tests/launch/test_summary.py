import json

from coopdrive.launch.summary import summary_dict
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
