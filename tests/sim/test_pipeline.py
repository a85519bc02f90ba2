"""The sim pieces together on the A270 map: a scripted leader, a follower driven by a plain ACC law through
the vehicle model, its sensors, the radio channel and the judge."""
import math

import numpy as np
import pytest

from coopdrive.services.sim import metrics
from coopdrive.services.sim.participants import IntentKind, ScriptedVehicle
from coopdrive.services.sim.profiles import PASSENGER_CAR
from coopdrive.services.sim.radio_channel import RadioChannel, RadioNode
from coopdrive.services.sim.channel_config import RadioChannelConfig
from coopdrive.services.sim.scenario_config import GCDC_2016_FINAL
from coopdrive.services.sim.sensor_config import SensorSuiteConfig
from coopdrive.services.sim.sensor_suite import SensorSuite
from coopdrive.services.sim.speed_profiles import PiecewiseSpeed, SpeedPoint
from coopdrive.services.sim.truth_series import TruthSeries
from coopdrive.services.sim.vehicle_model import VehicleModel, VehicleState
from coopdrive.services.sim.vehicle_truth import vehicle_truth
from coopdrive.services.sim.world_view import WorldView
from coopdrive.services.sim.world_profile import ideal

roadmap = pytest.importorskip("coopdrive.roadmap")

STEP_S = 0.05
HEADWAY_S, STANDSTILL_M = 1.5, 6.0


def test_a_follower_keeps_its_gap_behind_a_braking_leader_and_everything_is_observed():
    road = roadmap.RoadMap.load("a270")
    lanes = road.lanes_of_road("a270")
    leader = ScriptedVehicle("leader", 1, PASSENGER_CAR, lanes, 0, 300.0, PiecewiseSpeed(points=[
        SpeedPoint(time_s=3.0, speed_mps=16.7), SpeedPoint(time_s=8.0, speed_mps=11.1)]))
    x_m, y_m, heading = lanes[0].pose_at(300.0 - 35.0)
    start = VehicleState(x_m=x_m, y_m=y_m, heading_rad=heading, speed_mps=16.7)
    model = VehicleModel(ideal(PASSENGER_CAR), STEP_S, start)
    suite = SensorSuite(ideal(SensorSuiteConfig()), 3, "ego", PASSENGER_CAR, road.to_geodetic, GCDC_2016_FINAL, lanes)
    channel = RadioChannel(ideal(RadioChannelConfig()), np.random.default_rng(3))
    frames, radar_ranges, gnss_count, cams = [], [], 0, 0
    ego = vehicle_truth("ego", 2, model.state, PASSENGER_CAR, lanes)
    for k in range(1, 241):
        now_s = k * STEP_S
        lead = leader.step(now_s)
        for intent in leader.messages_due(now_s):
            assert intent.kind is IntentKind.CAM
            channel.deliver(b"cam", RadioNode("leader", lead.x_m, lead.y_m), [RadioNode("ego", ego.x_m, ego.y_m)],
                            now_s)
        cams += len(channel.due(now_s))
        gap_m = metrics.bumper_gap_m(lead, ego)
        # Rajamani's ACC law u = -(1/h)[(v - v_p) + lambda(-gap + h v + r)], lambda raised to 0.5 for a short run
        spacing_error_m = -gap_m + HEADWAY_S * ego.speed_mps + STANDSTILL_M
        accel = -((ego.speed_mps - lead.speed_mps) + 0.5 * spacing_error_m) / HEADWAY_S
        _, lateral_m, lane_heading, _ = lanes[0].project(ego.x_m, ego.y_m)
        heading_error = math.remainder(ego.heading_rad - lane_heading, math.tau)
        steer = -0.02 * lateral_m - 0.5 * heading_error
        model.step(accel, steer)
        ego = vehicle_truth("ego", 2, model.state, PASSENGER_CAR, lanes)
        outputs = suite.poll(now_s, WorldView(ego, [lead]), model.brake_pressure_bar())
        gnss_count += len(outputs.gnss)
        radar_ranges += [t.range_m for scan in outputs.radar for t in scan.tracks]
        frames.append((now_s, [lead, ego]))
    result = metrics.judge(TruthSeries.from_frames(frames), automated=["ego"])
    assert result["collisions"] == 0.0
    assert result["min_gap_m"] > 15.0
    assert result["max_abs_accel_mps2"] <= PASSENGER_CAR.max_decel_mps2
    assert abs(result["lateral_error_max_m"]) < 0.2
    assert gnss_count == pytest.approx(12.0 * 20, abs=2)
    assert len(radar_ranges) > 200 and min(radar_ranges) > 20.0
    assert cams > 230
