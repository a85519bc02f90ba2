import math

import pymap3d
import pytest

from coopdrive.geodesy import GeodeticOrigin
from coopdrive.v2x.generation import CamMode, VehicleDimensions
from coopdrive.v2x.generation import CamGenerator, CamTrigger, IclcmGenerator
from coopdrive.v2x.timebase import ItsClock, generation_delta_time_ms, tai_ms_from_utc
from coopdrive.v1 import control_pb2, ego_pb2, its_pb2, planner_pb2

from .streams import CLOCK

ORIGIN = GeodeticOrigin(lat_deg=51.4758, lon_deg=5.6247, alt_m=20.0)
STEP_S = 0.01


def generator(mode: CamMode) -> CamGenerator:
    return CamGenerator(mode, 1001, its_pb2.STATION_TYPE_PASSENGER_CAR, 1, ORIGIN, VehicleDimensions())


def drive(cam: CamGenerator, duration_s: float, ego_at=lambda t: ego_pb2.EgoState(speed_mps=0.0)) -> list[tuple]:
    """(time, trigger, content) of every CAM while checking every 10 ms."""
    sent = []
    for step in range(round(duration_s / STEP_S) + 1):
        now_s = step * STEP_S
        cam.on_ego_state(ego_at(now_s))
        content = cam.generate(now_s, CLOCK.tai_ms(now_s))
        if content is not None:
            sent.append((now_s, cam.last_trigger, content))
    return sent


def intervals(sent) -> list[float]:
    return [round(b[0] - a[0], 6) for a, b in zip(sent, sent[1:])]


def test_gcdc_mode_sends_a_cam_every_40_ms_even_standing_still():
    sent = drive(generator(CamMode.GCDC), 2.0)
    assert len(sent) == 51
    assert set(intervals(sent)) == {0.04}


def test_etsi_mode_sends_one_cam_per_second_when_nothing_changes():
    sent = drive(generator(CamMode.ETSI), 3.0)
    assert [t for t, _, _ in sent] == pytest.approx([0.0, 1.0, 2.0, 3.0])
    assert [trigger for _, trigger, _ in sent[1:]] == [CamTrigger.T_GEN_CAM] * 3


def test_etsi_mode_sends_a_cam_when_the_heading_turned_more_than_4_degrees():
    def turning(t):
        return ego_pb2.EgoState(heading_rad=math.radians(4.5) if t >= 0.3 else 0.0)
    sent = drive(generator(CamMode.ETSI), 0.5, turning)
    assert sent[1][0] == pytest.approx(0.3) and sent[1][1] == CamTrigger.HEADING


def test_etsi_mode_ignores_a_heading_change_below_4_degrees():
    sent = drive(generator(CamMode.ETSI), 0.9, lambda t: ego_pb2.EgoState(heading_rad=math.radians(3.5) * (t > 0.3)))
    assert len(sent) == 1


def test_etsi_mode_sends_a_cam_after_4_m_of_travel_at_most_10_times_a_second():
    # 100 m/s: 4 m every 40 ms, yet the minimum interval T_GenCamMin is 100 ms.
    sent = drive(generator(CamMode.ETSI), 1.0, lambda t: ego_pb2.EgoState(x_m=100.0 * t))
    assert set(intervals(sent)) == {0.1}
    assert sent[1][1] == CamTrigger.POSITION


def test_etsi_mode_sends_a_cam_when_the_speed_changed_more_than_half_a_metre_per_second():
    sent = drive(generator(CamMode.ETSI), 0.5, lambda t: ego_pb2.EgoState(speed_mps=0.6 if t >= 0.25 else 0.0))
    assert sent[1][0] == pytest.approx(0.25) and sent[1][1] == CamTrigger.SPEED


def test_etsi_mode_keeps_the_dynamics_interval_for_three_more_cams_then_falls_back_to_one_second():
    # One speed step at 0.2 s: CAMs at 0.2 s intervals three times, then 1 s.
    sent = drive(generator(CamMode.ETSI), 2.5, lambda t: ego_pb2.EgoState(speed_mps=1.0 if t >= 0.2 else 0.0))
    assert [t for t, _, _ in sent] == pytest.approx([0.0, 0.2, 0.4, 0.6, 0.8, 1.8])


def test_the_low_frequency_container_is_sent_every_500_ms():
    sent = drive(generator(CamMode.GCDC), 1.2)
    with_low = [t for t, _, content in sent if content.HasField("low_frequency")]
    assert with_low == pytest.approx([0.0, 0.52, 1.04])


def test_the_cam_position_is_the_centre_of_the_front_ahead_of_the_rear_axle_converted_with_the_origin():
    cam = generator(CamMode.GCDC)
    cam.on_ego_state(ego_pb2.EgoState(x_m=0.0, y_m=1000.0, heading_rad=0.1, speed_mps=10.0, accel_mps2=-0.5,
                                      yaw_rate_radps=0.05, position_std_m=0.1))
    content = cam.generate(0.0, CLOCK.tai_ms(0.0))
    position = content.reference_position
    ahead_m = VehicleDimensions().rear_axle_location_m
    front_east_m, front_north_m = ahead_m * math.cos(0.1), 1000.0 + ahead_m * math.sin(0.1)
    latitude_deg, longitude_deg, _ = pymap3d.enu2geodetic(front_east_m, front_north_m, 0.0, 51.4758, 5.6247, 20.0)
    # 2e-7 deg is about 2 cm: the reference point is placed with a spherical Earth over 3.5 m.
    assert position.latitude_deg == pytest.approx(latitude_deg, abs=2e-7)
    assert position.longitude_deg == pytest.approx(longitude_deg, abs=3e-7)
    assert position.semi_major_confidence_m == pytest.approx(0.245, abs=1e-3)
    hf = content.high_frequency
    assert (hf.heading_rad, hf.speed_mps, hf.longitudinal_acceleration_mps2) == (0.1, 10.0, -0.5)
    assert hf.curvature_per_m == pytest.approx(0.005)


def test_the_cam_position_starts_from_the_ego_latitude_and_longitude_when_the_ego_state_has_them():
    cam = generator(CamMode.GCDC)
    cam.on_ego_state(ego_pb2.EgoState(x_m=500.0, latitude_deg=57.7, longitude_deg=11.97, heading_rad=0.0))
    position = cam.generate(0.0, CLOCK.tai_ms(0.0)).reference_position
    _, front_longitude_deg, _ = pymap3d.enu2geodetic(VehicleDimensions().rear_axle_location_m, 0.0, 0.0,
                                                     57.7, 11.97, 0.0)
    assert position.latitude_deg == pytest.approx(57.7, abs=1e-9)
    assert position.longitude_deg == pytest.approx(front_longitude_deg, abs=3e-7)


def test_generation_delta_time_is_the_tai_time_of_sim_time_plus_the_epoch():
    from datetime import datetime, timezone

    epoch = datetime(2016, 5, 28, 10, 0, 0, tzinfo=timezone.utc)
    clock = ItsClock(epoch.timestamp())
    cam = generator(CamMode.GCDC)
    cam.on_ego_state(ego_pb2.EgoState())
    content = cam.generate(12.5, clock.tai_ms(12.5))
    assert content.generation_delta_time_ms == generation_delta_time_ms(tai_ms_from_utc(epoch) + 12_500)


def cam_front_at(ego: ego_pb2.EgoState, now_s: float) -> tuple[float, float]:
    cam = generator(CamMode.GCDC)
    cam.on_ego_state(ego)
    content = cam.generate(now_s, CLOCK.tai_ms(now_s))
    assert content.generation_delta_time_ms == generation_delta_time_ms(CLOCK.tai_ms(now_s))
    return content.reference_position.latitude_deg, content.reference_position.longitude_deg


def test_a_position_estimate_40_ms_old_is_carried_forward_to_the_generation_time():
    # 20 m/s due east: 0.8 m further east than the same estimate sent at once.
    ego = ego_pb2.EgoState(x_m=0.0, y_m=0.0, heading_rad=0.0, speed_mps=20.0)
    ego.header.sample_time_s = 12.46
    late_lat, late_lon = cam_front_at(ego, 12.5)
    ego.header.sample_time_s = 12.5
    fresh_lat, fresh_lon = cam_front_at(ego, 12.5)
    east_m, north_m, _ = pymap3d.geodetic2enu(late_lat, late_lon, 20.0, fresh_lat, fresh_lon, 20.0)
    assert east_m == pytest.approx(0.8, abs=0.01) and north_m == pytest.approx(0.0, abs=0.01)


def test_a_stale_position_estimate_is_not_carried_forward():
    ego = ego_pb2.EgoState(x_m=0.0, y_m=0.0, heading_rad=0.0, speed_mps=20.0)
    ego.header.sample_time_s = 2.0
    stale = cam_front_at(ego, 12.5)
    ego.header.sample_time_s = 12.5
    assert stale == pytest.approx(cam_front_at(ego, 12.5))


def test_no_cam_is_generated_before_the_first_ego_state():
    assert generator(CamMode.GCDC).generate(0.0, 0) is None


def test_the_iclcm_is_sent_at_25_hz_with_the_planner_intent_and_the_control_fields():
    iclcm = IclcmGenerator(1001, VehicleDimensions(rear_axle_location_m=3.6))
    behaviour = planner_pb2.BehaviourRequest()
    behaviour.targets.add(object_id=7, station_id=1002, role=planner_pb2.TARGET_ROLE_PREDECESSOR)
    behaviour.iclcm.CopyFrom(planner_pb2.IclcmIntent(forward_id=1002, backward_id=1000, merge_request=True,
                                                     platoon_id=1, intention=1, participants_ready=True))
    iclcm.on_behaviour(behaviour)
    iclcm.on_command(control_pb2.ControlCommand(
        longitudinal_mode=control_pb2.LONGITUDINAL_MODE_CACC, accel_request_mps2=0.4, time_gap_s=0.5,
        cruise_speed_mps=22.2, response_time_constant_s=0.5, response_time_delay_s=0.2, gap_m=12.0))
    sent = [(step * STEP_S, content) for step in range(101)
            if (content := iclcm.generate(step * STEP_S, CLOCK.tai_ms(step * STEP_S))) is not None]
    assert len(sent) == 26
    content = sent[0][1]
    assert content.controller_type == its_pb2.CONTROLLER_TYPE_CACC
    assert (content.target_longitudinal_acceleration_mps2, content.time_headway_s, content.cruise_speed_mps) == \
        (0.4, 0.5, 22.2)
    assert (content.response_time_constant_s, content.response_time_delay_s) == (0.5, 0.2)
    assert (content.mio_id, content.mio_range_m, content.rear_axle_location_m) == (1002, 12.0, 3.6)
    assert (content.forward_id, content.backward_id, content.merge_request, content.platoon_id) == (1002, 1000, True, 1)
    assert content.intention == its_pb2.INTENTION_STRAIGHT
    assert content.has_low_frequency and content.participants_ready
    assert not sent[1][1].has_low_frequency


def test_the_iclcm_says_manual_until_control_sends_a_command():
    iclcm = IclcmGenerator(1001, VehicleDimensions())
    iclcm.on_behaviour(planner_pb2.BehaviourRequest())
    assert iclcm.generate(0.0, 0).controller_type == its_pb2.CONTROLLER_TYPE_MANUAL


def test_no_cam_is_sent_while_the_localisation_is_lost():
    sent = drive(generator(CamMode.GCDC), 1.0,
                 ego_at=lambda t: ego_pb2.EgoState(speed_mps=10.0, mode=ego_pb2.LOCALISATION_MODE_LOST))
    assert sent == []
