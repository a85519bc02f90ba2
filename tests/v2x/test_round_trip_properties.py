import math

from hypothesis import given, settings
from hypothesis import strategies as st

from coopdrive.v2x.its_pdu import ItsCodec, ItsMessageId
from coopdrive.v2x.mapping.cam import cam_from_asn, cam_to_asn
from coopdrive.v2x.mapping.iclcm import iclcm_from_asn, iclcm_to_asn
from coopdrive.v1 import its_pb2

CODEC = ItsCodec()


def through_the_wire(message_id, to_asn, from_asn, content):
    return from_asn(CODEC.decode(CODEC.encode(message_id, to_asn(content)))[1])


@settings(max_examples=150, deadline=None)
@given(latitude_deg=st.floats(-90, 90), longitude_deg=st.floats(-180, 180), speed_mps=st.floats(0, 163.82),
       heading_rad=st.floats(-math.pi, math.pi), yaw_rate_radps=st.floats(-5.7, 5.7))
def test_cam_kinematics_come_back_within_half_a_wire_unit(latitude_deg, longitude_deg, speed_mps, heading_rad,
                                                           yaw_rate_radps):
    content = its_pb2.CamContent(protocol_version=1, station_id=3)
    content.reference_position.latitude_deg, content.reference_position.longitude_deg = latitude_deg, longitude_deg
    hf = content.high_frequency
    hf.speed_mps, hf.heading_rad, hf.yaw_rate_radps = speed_mps, heading_rad, yaw_rate_radps
    back = through_the_wire(ItsMessageId.CAM, cam_to_asn, cam_from_asn, content)
    assert abs(back.reference_position.latitude_deg - latitude_deg) <= 0.5e-7 + 1e-12
    assert abs(back.reference_position.longitude_deg - longitude_deg) <= 0.5e-7 + 1e-12
    assert abs(back.high_frequency.speed_mps - speed_mps) <= 0.005 + 1e-9
    assert abs(math.remainder(back.high_frequency.heading_rad - heading_rad, math.tau)) <= math.radians(0.05) + 1e-9
    assert abs(back.high_frequency.yaw_rate_radps - yaw_rate_radps) <= math.radians(0.005) + 1e-9


@settings(max_examples=150, deadline=None)
@given(gap_s=st.floats(0, 36), cruise_mps=st.floats(0, 50), accel_mps2=st.floats(-10, 10),
       bearing_rad=st.floats(-3.142, 3.142), range_m=st.floats(0, 655.34), lane=st.integers(1, 3))
def test_iclcm_values_come_back_within_half_a_wire_unit(gap_s, cruise_mps, accel_mps2, bearing_rad, range_m, lane):
    content = its_pb2.IclcmContent(
        protocol_version=1, time_headway_s=gap_s, cruise_speed_mps=cruise_mps,
        target_longitudinal_acceleration_mps2=accel_mps2, mio_bearing_rad=bearing_rad, mio_range_m=range_m,
        lane=lane, intention=its_pb2.INTENTION_STRAIGHT)
    back = through_the_wire(ItsMessageId.ICLCM, iclcm_to_asn, iclcm_from_asn, content)
    assert abs(back.time_headway_s - gap_s) <= 0.05 + 1e-9
    assert abs(back.cruise_speed_mps - cruise_mps) <= 0.005 + 1e-9
    assert abs(back.target_longitudinal_acceleration_mps2 - accel_mps2) <= 0.005 + 1e-9
    assert abs(back.mio_bearing_rad - bearing_rad) <= 0.001 + 1e-9
    assert abs(back.mio_range_m - range_m) <= 0.005 + 1e-9
    assert back.lane == lane
