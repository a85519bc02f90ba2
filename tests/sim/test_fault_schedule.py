import datetime as dt

import numpy as np

from coopdrive.services.sim.channel_config import RadioChannelConfig
from coopdrive.services.sim.fault_config import (CanErrorBurst, FixDowngrade, GnssJump, GnssOutage, PartnerSilent,
                                                 SensorDropout, SensorName, V2vCorruption, V2vLoss)
from coopdrive.services.sim.fault_schedule import FaultSchedule
from coopdrive.services.sim.profiles import PASSENGER_CAR
from coopdrive.services.sim.radio_channel import RadioChannel
from coopdrive.services.sim.road_geometry import straight_road
from coopdrive.services.sim.sensor_config import FixModeName, SensorSuiteConfig
from coopdrive.services.sim.sensor_suite import SensorSuite
from coopdrive.services.sim.world_view import WorldView
from coopdrive.v1 import gnss_pb2, sim_pb2


def _suite(seed=1):
    return SensorSuite(SensorSuiteConfig(), seed, "ego", PASSENGER_CAR, lambda x, y, z: (51.0, 5.0, z),
                       dt.datetime(2016, 5, 28, tzinfo=dt.timezone.utc), straight_road(2))


def test_overlapping_fix_downgrades_fall_back_in_order_and_an_outage_ends():
    suite = _suite()
    schedule = FaultSchedule([
        FixDowngrade(type="fix_downgrade", vehicle_id="ego", fix_mode=FixModeName.SBAS, start_s=1, end_s=5),
        FixDowngrade(type="fix_downgrade", vehicle_id="ego", fix_mode=FixModeName.SINGLE, start_s=2, end_s=3),
        GnssOutage(type="gnss_outage", vehicle_id="ego", start_s=4, end_s=4.5)])
    modes = []
    for t in (0.0, 1.0, 2.0, 3.0, 4.2, 6.0):
        schedule.update(t, {"ego": suite})
        modes.append(suite.gnss.effective_fix_mode)
    assert modes == [gnss_pb2.FIX_MODE_RTK_FIXED, gnss_pb2.FIX_MODE_SBAS, gnss_pb2.FIX_MODE_SINGLE,
                     gnss_pb2.FIX_MODE_SBAS, gnss_pb2.FIX_MODE_NO_FIX, gnss_pb2.FIX_MODE_RTK_FIXED]


def test_sensor_dropouts_and_can_error_bursts_silence_the_sensors_meanwhile():
    suite = _suite()
    schedule = FaultSchedule([SensorDropout(type="sensor_dropout", vehicle_id="ego", sensor=SensorName.RADAR,
                                            start_s=0, end_s=1),
                              CanErrorBurst(type="can_error_burst", vehicle_id="ego", start_s=0, end_s=1)])
    schedule.update(0.5, {"ego": suite})
    ego = sim_pb2.VehicleTruth(vehicle_id="ego", speed_mps=10.0, length_m=4.5, width_m=1.8)
    outputs = suite.poll(0.5, WorldView(ego, []), 0.0)
    assert outputs.radar == [] and outputs.can_state == [] and outputs.gnss
    schedule.update(1.5, {"ego": suite})
    outputs = suite.poll(1.5, WorldView(ego, []), 0.0)
    assert outputs.radar and outputs.can_state


def test_channel_faults_apply_while_active_and_integrator_faults_are_reported():
    channel = RadioChannel(RadioChannelConfig(), np.random.default_rng(0))
    partner = PartnerSilent(type="partner_silent", vehicle_id="b", start_s=1, end_s=2)
    schedule = FaultSchedule([V2vLoss(type="v2v_loss", vehicle_id="a", start_s=1, end_s=2),
                              V2vCorruption(type="v2v_corruption", corruption_probability=0.5, start_s=1, end_s=2),
                              partner])
    started = schedule.update(1.0, {}, channel)
    assert {type(t.fault).__name__ for t in started if t.started} == {"V2vLoss", "V2vCorruption", "PartnerSilent"}
    assert channel.node_loss_probability == {"a": 1.0} and channel.corruption_probability == 0.5
    ended = schedule.update(2.0, {}, channel)
    assert all(not t.started for t in ended) and len(ended) == 3
    assert channel.node_loss_probability == {} and channel.corruption_probability == 0.0


def test_the_same_seed_gives_the_same_sensor_outputs():
    ego = sim_pb2.VehicleTruth(vehicle_id="ego", speed_mps=10.0, x_m=5.0, length_m=4.5, width_m=1.8)
    lead = sim_pb2.VehicleTruth(vehicle_id="lead", speed_mps=9.0, x_m=30.0, length_m=4.5, width_m=1.8)
    a, b = _suite(seed=9), _suite(seed=9)
    for k in range(20):
        out_a = a.poll(k * 0.05, WorldView(ego, [lead]), 0.0)
        out_b = b.poll(k * 0.05, WorldView(ego, [lead]), 0.0)
        assert out_a.radar == out_b.radar and out_a.lidar == out_b.lidar
        assert [g.data for g in out_a.gnss] == [g.data for g in out_b.gnss]


def test_a_gnss_jump_moves_the_reported_antenna_position_by_its_offset_while_it_lasts():
    suite = _suite()
    schedule = FaultSchedule([GnssJump(type="gnss_jump", vehicle_id="ego", east_m=5.0, north_m=-2.0,
                                       start_s=1, end_s=2)])
    ego = sim_pb2.VehicleTruth(vehicle_id="ego", speed_mps=0.0, length_m=4.5, width_m=1.8)
    reported = {}
    for t in np.arange(0.0, 3.0, 0.05):
        schedule.update(t, {"ego": suite})
        for output in suite.poll(t, WorldView(ego, []), 0.0).gnss:
            reported[round(output.sample_time_s, 2)] = (output.measured_x_m, output.measured_y_m)
    during = [xy for t, xy in reported.items() if 1.2 <= t < 1.9]
    outside = [xy for t, xy in reported.items() if t < 0.9 or t >= 2.2]
    assert during and outside
    assert all(abs(x - 5.0) < 0.1 and abs(y + 2.0) < 0.1 for x, y in during)
    assert all(abs(x) < 0.1 and abs(y) < 0.1 for x, y in outside)
    assert suite.gnss.effective_fix_mode == gnss_pb2.FIX_MODE_RTK_FIXED


def test_a_ramped_gnss_jump_moves_on_at_every_update_though_no_fault_starts_or_ends():
    suite = _suite()
    jump = GnssJump(type="gnss_jump", vehicle_id="ego", east_m=4.0, start_s=1.0, end_s=5.0, ramp_s=1.0)
    schedule = FaultSchedule([jump])
    offsets = []
    for t in (1.25, 1.5, 1.75, 2.5):
        schedule.update(t, {"ego": suite})
        offsets.append(suite.gnss.offset_east_m)
    assert offsets == [jump.offset_at(t)[0] for t in (1.25, 1.5, 1.75, 2.5)]
    assert offsets[0] < offsets[1] < offsets[2] < offsets[3] == 4.0
