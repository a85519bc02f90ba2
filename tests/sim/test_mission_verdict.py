"""MissionJudge: a run fails on a collision, and on its mission's goal with the vehicles that missed it."""

from coopdrive.services.sim.mission_verdict import MissionJudge
from coopdrive.services.sim.scenario_config import parse_scenario
from coopdrive.v1 import sim_pb2


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


def test_a_merge_fails_naming_who_is_still_in_the_closed_lane():
    roadworks = [{"unit_id": "rsu", "station_id": 9, "x_m": 0, "y_m": 0,
                  "events": [{"kind": "roadworks", "time_s": 1, "closed_lane": 1}]}]
    judge = MissionJudge(config("merge", roadside_units=roadworks), ["a", "b"])
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
