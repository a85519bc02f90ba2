"""MissionJudge: a run fails on a collision, and on its mission's goal with the vehicles that missed it."""

import math

from coopdrive.services.sim.mission_verdict import MissionJudge
from coopdrive.services.sim.scenario_config import parse_scenario
from coopdrive.v1 import actuation_pb2, sim_pb2


def config(mission, **extra):
    data = {"name": "t", "map": "a270", "duration_s": 10, "mission": mission,
            "vehicles": [{"vehicle_id": "a", "station_id": 2, "lane": 1, "station_m": 0, "speed_mps": 10},
                         {"vehicle_id": "b", "station_id": 3, "lane": 0, "station_m": 20, "speed_mps": 10}]}
    data.update(extra)
    return parse_scenario(data)


def truth(*vehicles):
    return sim_pb2.GroundTruth(vehicles=[sim_pb2.VehicleTruth(length_m=4.5, width_m=1.8, speed_mps=10, **v)
                                         for v in vehicles])


def test_two_vehicles_that_touch_are_one_collision_however_long_they_stay_in_contact():
    judge = MissionJudge(config("follow"), ["a", "b"])
    apart = truth({"vehicle_id": "a", "x_m": 0}, {"vehicle_id": "b", "x_m": 20})
    touching = truth({"vehicle_id": "a", "x_m": 0}, {"vehicle_id": "b", "x_m": 3})
    for time_s, frame in enumerate([apart, touching, touching, touching, apart, touching]):
        judge.observe(float(time_s), frame)
    assert judge.collisions == 2
    assert judge.verdict() == (False, "2 collision(s)")


def test_a_stack_vehicle_handed_back_to_its_driver_fails_the_run_naming_it_and_when():
    judge = MissionJudge(config("follow"), ["a", "b"])
    judge.observe(0.0, truth({"vehicle_id": "a", "x_m": 0}, {"vehicle_id": "b", "x_m": 20}))
    judge.observe_automation("b", False, 0.0)  # not engaged yet: the driver still has it, nothing lost
    for time_s in (0.1, 0.2):
        judge.observe_automation("a", True, time_s)
        judge.observe_automation("b", True, time_s)
    judge.observe_automation("b", False, 19.1)
    judge.observe_automation("b", False, 19.2)
    assert judge.verdict() == (False, "automation lost: b at 19.1 s")
    assert judge.metrics()["automation_lost"] == 1.0


def test_a_safe_stop_no_fault_explains_fails_the_run_naming_the_vehicle_and_when():
    judge = MissionJudge(config("follow"), ["a", "b"])
    judge.observe(0.0, truth({"vehicle_id": "a", "x_m": 0}, {"vehicle_id": "b", "x_m": 20}))
    for time_s, mode in ((0.1, actuation_pb2.DRIVING_MODE_AUTONOMOUS), (32.0, actuation_pb2.DRIVING_MODE_SAFE_STOP),
                         (32.1, actuation_pb2.DRIVING_MODE_SAFE_STOP)):
        judge.observe_mode("a", mode, time_s)
    assert judge.verdict() == (False, "safe stop: a at 32.0 s")
    assert judge.metrics()["safe_stops"] == 1.0


def test_a_safe_stop_after_a_fault_of_that_vehicle_is_its_reaction_not_a_failure():
    faults = [{"type": "gnss_outage", "vehicle_id": "a", "start_s": 30.0}]
    judge = MissionJudge(config("follow", faults=faults), ["a", "b"])
    judge.observe(0.0, truth({"vehicle_id": "a", "x_m": 0}, {"vehicle_id": "b", "x_m": 20}))
    judge.observe_mode("a", actuation_pb2.DRIVING_MODE_SAFE_STOP, 32.0)
    judge.observe_mode("b", actuation_pb2.DRIVING_MODE_SAFE_STOP, 33.0)
    assert judge.verdict() == (False, "safe stop: b at 33.0 s")


ROADWORKS_AT_500_M = [{"unit_id": "rsu", "station_id": 9, "x_m": 0, "y_m": 0,
                       "events": [{"kind": "roadworks", "time_s": 1, "closed_lane": 1, "x_m": 500, "y_m": 0,
                                   "length_m": 300}]}]


def merge_judge():
    return MissionJudge(config("merge", roadside_units=ROADWORKS_AT_500_M), ["a", "b"])


def test_a_merge_fails_naming_who_is_still_in_the_closed_lane():
    judge = merge_judge()
    judge.observe(0.0, truth({"vehicle_id": "a", "x_m": 0, "lane_index": 1},
                             {"vehicle_id": "b", "x_m": 30, "lane_index": 0}))
    assert judge.verdict() == (False, "merge not completed: a still in the closed lane at the end")
    judge.observe(1.0, truth({"vehicle_id": "a", "x_m": 10, "lane_index": 0},
                             {"vehicle_id": "b", "x_m": 40, "lane_index": 0}))
    assert judge.verdict() == (True, "")


def test_a_follow_run_without_contact_passes_and_reports_its_gap():
    judge = MissionJudge(config("follow"), ["a", "b"])
    for time_s in range(5):
        judge.observe(float(time_s), truth({"vehicle_id": "a", "x_m": 0, "lane_index": 0},
                                           {"vehicle_id": "b", "x_m": 20, "lane_index": 0}))
    assert judge.verdict() == (True, "")
    assert judge.metrics()["collisions"] == 0


def test_a_merge_fails_naming_who_drove_into_the_road_works_even_after_leaving_them():
    judge = merge_judge()
    judge.observe(0.0, truth({"vehicle_id": "a", "x_m": 520, "lane_index": 1}, {"vehicle_id": "b", "x_m": 0}))
    judge.observe(1.0, truth({"vehicle_id": "a", "x_m": 830, "lane_index": 0}, {"vehicle_id": "b", "x_m": 10}))
    assert judge.verdict() == (False, "a drove into the road works")


def lane_change(judge, start_s, duration_s):
    """Vehicle a leaves lane 1's centre at start_s and is centred in lane 0 duration_s later."""
    frames = [(start_s - 1.0, 1, 0.0), (start_s, 1, 0.5), (start_s + duration_s / 2, 0, 1.0),
              (start_s + duration_s, 0, 0.1)]
    for time_s, lane, offset_m in frames:
        judge.observe(time_s, truth({"vehicle_id": "a", "x_m": 100 + time_s, "lane_index": lane,
                                     "lateral_offset_m": offset_m},
                                    {"vehicle_id": "b", "x_m": 900 + time_s, "lane_index": 0}))


def test_the_lane_change_time_runs_from_leaving_the_lane_centre_to_settling_in_the_open_lane():
    judge = merge_judge()
    lane_change(judge, start_s=5.0, duration_s=6.0)
    assert judge.metrics()["lane_change_time_s"] == 6.0
    assert judge.verdict() == (True, "")


def test_the_merge_time_runs_from_the_road_works_notice_to_the_last_merger_settled():
    judge = merge_judge()
    lane_change(judge, start_s=5.0, duration_s=6.0)
    assert judge.metrics()["merge_time_s"] == 11.0 - 1.0  # the roadside unit announces the works at 1 s


def test_a_lane_change_slower_than_10_s_fails_naming_the_vehicle_and_its_time():
    judge = merge_judge()
    lane_change(judge, start_s=5.0, duration_s=12.0)
    assert judge.verdict() == (False, "lane change too slow: a 12.0 s")


def intersection_config():
    return parse_scenario({
        "name": "t", "map": "intersection", "duration_s": 10, "mission": "intersection",
        "vehicles": [{"vehicle_id": "a", "station_id": 2, "road": "main_eastbound", "lane": 0, "station_m": 0,
                      "speed_mps": 10},
                     {"vehicle_id": "o", "station_id": 3, "role": "scripted", "road": "side_northbound", "lane": 0,
                      "station_m": 0, "speed_mps": 0}]})


def test_an_intersection_run_passes_once_the_stack_has_crossed_the_competition_zone():
    judge = MissionJudge(intersection_config(), ["a"])
    for time_s, x_m in enumerate([-150, -60, 0, 60, 120]):
        judge.observe(float(time_s), truth({"vehicle_id": "a", "x_m": x_m, "y_m": -1.75},
                                           {"vehicle_id": "o", "x_m": 1.75, "y_m": -40}))
        if x_m < 120:
            assert judge.verdict() == (False, "intersection not crossed by a")
    assert judge.verdict() == (True, "")
    assert judge.metrics()["crossing_time_s"] == 3.0


NORTH = 1.5708


def test_an_intersection_run_fails_on_entering_the_safety_circle_of_a_crossing_vehicle():
    judge = MissionJudge(intersection_config(), ["a"])
    for time_s, x_m in enumerate([-150, -60, 0, 60, 120]):
        judge.observe(float(time_s), truth({"vehicle_id": "a", "x_m": x_m, "y_m": -1.75},
                                           {"vehicle_id": "o", "x_m": 1.75, "y_m": -8, "heading_rad": NORTH}))
    assert judge.verdict() == (False, "1 safety circle violation(s) between crossing vehicles")


def test_passing_a_car_in_the_opposite_lane_is_no_safety_circle_violation():
    judge = MissionJudge(intersection_config(), ["a"])
    for time_s, x_m in enumerate([-150, -60, 0, 60, 120]):
        judge.observe(float(time_s), truth({"vehicle_id": "a", "x_m": x_m, "y_m": -1.75},
                                           {"vehicle_id": "o", "x_m": -x_m, "y_m": 1.75, "heading_rad": 3.1416}))
    assert judge.metrics()["safety_circle_violations"] == 1
    assert judge.verdict() == (True, "")


def amplifying_platoon(faults, excitation_hz=0.2):
    """b leads a in one lane; a's 0.2 Hz speed wave is twice b's: a string gain of 2. excitation_hz: the
    excitation the scenario declares (None: a steady leader, as in platoon40)."""
    judging = {"platoon": ["b", "a"], "string_end_s": 10}
    if excitation_hz is not None:
        judging["string_frequency_hz"] = excitation_hz
    judge = MissionJudge(config("platoon", faults=faults, judging=judging), ["a", "b"])
    for k in range(101):
        t = 0.1 * k
        wave = math.sin(2 * math.pi * 0.2 * t)
        judge.observe(t, sim_pb2.GroundTruth(vehicles=[
            sim_pb2.VehicleTruth(vehicle_id="b", x_m=100 + 10 * t, speed_mps=10 + wave, length_m=4.5, width_m=1.8),
            sim_pb2.VehicleTruth(vehicle_id="a", x_m=10 * t, speed_mps=10 + 2 * wave, length_m=4.5, width_m=1.8)]))
    return judge


def test_a_platoon_that_amplifies_the_wave_fails_as_string_unstable():
    assert amplifying_platoon([]).verdict() == (False, "string unstable: string gain 2.000 >= 1")


def test_with_every_v2v_link_cut_the_string_gain_is_reported_but_only_a_collision_fails_the_run():
    judge = amplifying_platoon([{"type": "v2v_loss", "start_s": 2.0, "loss_probability": 1.0}])
    assert judge.metrics()["string_gain"] > 1.9
    assert judge.verdict() == (True, "")


def test_behind_a_leader_with_no_declared_excitation_the_string_gain_is_reported_but_not_judged():
    judge = amplifying_platoon([], excitation_hz=None)
    assert judge.metrics()["string_gain"] > 1.9
    assert judge.verdict() == (True, "")


def test_partial_v2v_loss_leaves_the_string_gain_judged():
    judge = amplifying_platoon([{"type": "v2v_loss", "start_s": 2.0, "loss_probability": 0.2}])
    assert not judge.verdict()[0]


def emergency_judge():
    vehicles = [{"vehicle_id": "a", "station_id": 2, "lane": 1, "station_m": 100, "speed_mps": 10},
                {"vehicle_id": "e", "station_id": 9, "role": "emergency", "lane": 1, "station_m": 0,
                 "speed_mps": 20, "lateral_offset_m": -1.75, "siren": {"on_s": 0}}]
    return MissionJudge(config("emergency", vehicles=vehicles), ["a"])


def corridor(judge, frames):
    """frames: (time_s, a's station and lateral offset, the emergency vehicle's station)."""
    for time_s, a_station_m, a_offset_m, e_station_m in frames:
        judge.observe(time_s, truth({"vehicle_id": "a", "station_m": a_station_m, "lane_index": 1,
                                     "lateral_offset_m": a_offset_m, "x_m": a_station_m},
                                    {"vehicle_id": "e", "station_m": e_station_m, "lane_index": 1,
                                     "lateral_offset_m": -1.75, "x_m": e_station_m, "y_m": 3.0}))


def test_an_emergency_run_whose_corridor_stays_open_fails_naming_who_is_still_aside():
    judge = emergency_judge()
    corridor(judge, [(0.0, 100, 0.0, 0), (5.0, 150, 0.8, 140), (10.0, 200, 0.8, 240)])
    assert judge.verdict() == (False, "corridor not closed: a still off the lane centre at the end")


def test_the_corridor_closes_once_the_vehicles_are_back_on_their_lane_centres_and_its_time_is_reported():
    judge = emergency_judge()
    corridor(judge, [(0.0, 100, 0.0, 0), (5.0, 150, 0.8, 140), (10.0, 200, 0.8, 240), (13.0, 230, 0.1, 300)])
    assert judge.verdict() == (True, "")
    assert judge.metrics()["corridor_close_time_s"] == 3.0


def test_the_live_verdict_reports_every_error_figure_as_coopdrive_score_does_on_the_same_truth():
    from coopdrive.judging.run_messages import RunMessages
    from coopdrive.judging.score import JudgingParameters, score_messages
    from tests.judging.synthetic import truth_at, two_car_frames

    frames = [truth_at(time_s, vehicles) for time_s, vehicles in two_car_frames()]
    cars = [{"vehicle_id": "leader", "station_id": 2, "lane": 0, "station_m": 30, "speed_mps": 10},
            {"vehicle_id": "follower", "station_id": 3, "lane": 0, "station_m": 0, "speed_mps": 12}]
    judge = MissionJudge(config("follow", vehicles=cars, judging={"platoon": ["leader", "follower"]}), ["follower"])
    for frame in frames:
        judge.observe(frame.header.sample_time_s, frame)
    live = judge.metrics()
    scored = score_messages(RunMessages(truth=frames), JudgingParameters(platoon=("leader", "follower")))
    for figure in ("speed_error", "spacing_error", "lateral_error"):
        keys = [key for key in scored if key.startswith(figure)]
        assert len(keys) == 6, keys
        for key in keys:
            assert live[key] == scored[key], key
    assert live["speed_error_kmh"] == 7.2


def test_a_scenario_that_declares_no_platoon_reports_no_spacing_or_speed_error():
    judge = MissionJudge(config("follow"), ["a", "b"])
    for time_s in range(5):
        judge.observe(float(time_s), truth({"vehicle_id": "a", "x_m": 0, "station_m": 0, "lane_index": 0},
                                           {"vehicle_id": "b", "x_m": 60, "station_m": 60, "lane_index": 0}))
    figures = judge.metrics()
    assert not [key for key in figures if key.startswith(("spacing_error", "speed_error"))]
    assert "lateral_error_m" in figures
