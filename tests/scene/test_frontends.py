import math

import numpy as np
import pytest

from coopdrive.services.scene.config import CameraConfig, RadarConfig, SonarConfig, V2vConfig
from coopdrive.services.scene.frontends import (
    CameraFrontEnd,
    RadarFrontEnd,
    RejectCounter,
    SonarFrontEnd,
    V2vFrontEnd,
    nearest_point_to_rear_centre,
)
from coopdrive.services.scene.measurement import EgoPose, V2vObservation
from coopdrive.v1 import ego_pb2, sensors_pb2


def pose(time_s=1.0, x_m=100.0, y_m=-20.0, heading_rad=0.0, speed_mps=10.0):
    return EgoPose(time_s=time_s, x_m=x_m, y_m=y_m, heading_rad=heading_rad, speed_mps=speed_mps,
                   yaw_rate_radps=0.0, accel_mps2=0.0, position_cov_m2=np.eye(2) * 0.01)


def test_radar_range_rate_becomes_an_absolute_speed_along_the_beam():
    frame = sensors_pb2.RadarTracks()
    frame.tracks.add(track_id=3, range_m=30.0, azimuth_rad=0.0, range_rate_mps=2.0, width_m=1.8)
    (meas,) = RadarFrontEnd(RadarConfig(), RejectCounter()).measurements(frame, pose())
    assert meas.position_m == pytest.approx([130.0, -20.0])
    assert meas.radial_speed_mps == pytest.approx(12.0)
    assert meas.cov_m2[0, 0] == pytest.approx(0.3**2 + 0.01)


def test_radar_tracks_that_are_not_numbers_are_skipped_and_counted():
    frame = sensors_pb2.RadarTracks()
    frame.tracks.add(track_id=1, range_m=float("nan"), azimuth_rad=0.0)
    frame.tracks.add(track_id=2, range_m=20.0, azimuth_rad=0.1)
    rejects = RejectCounter()
    assert len(RadarFrontEnd(RadarConfig(), rejects).measurements(frame, pose())) == 1
    assert sum(rejects.counts.values()) == 1


def test_camera_range_is_trusted_less_than_its_bearing_and_lane_markings_pass_through():
    frame = sensors_pb2.CameraFrame()
    frame.header.sample_time_s = 1.0
    frame.detections.add(detection_id=1, object_class=sensors_pb2.OBJECT_CLASS_TRUCK, x_m=40.0, y_m=0.0,
                         width_m=2.5, confidence=0.8)
    frame.lane_markings.add(side=sensors_pb2.LANE_SIDE_LEFT, c0_m=1.8, quality=0.9)
    front_end = CameraFrontEnd(CameraConfig(), RejectCounter())
    (meas,) = front_end.measurements(frame, pose())
    assert meas.object_class == sensors_pb2.OBJECT_CLASS_TRUCK
    assert meas.quality == pytest.approx(0.8)
    assert meas.cov_m2[0, 0] > meas.cov_m2[1, 1]  # along the range (east) versus across
    markings = front_end.lane_markings(frame)
    assert markings.time_s == 1.0
    assert markings.markings[0].c0_m == pytest.approx(1.8)


def test_a_sonar_echo_is_a_fuzzy_near_field_object_and_every_sonar_gives_a_free_range():
    frame = sensors_pb2.SonarRanges()
    frame.ranges.add(sensor_index=1, mount_x_m=2.0, mount_y_m=0.9, mount_yaw_rad=math.pi / 2, range_m=1.5,
                     max_range_m=4.0, echo=True)
    frame.ranges.add(sensor_index=0, mount_x_m=2.0, mount_y_m=-0.9, mount_yaw_rad=-math.pi / 2, range_m=0.0,
                     max_range_m=4.0, echo=False)
    front_end = SonarFrontEnd(SonarConfig(), RejectCounter())
    (meas,) = front_end.measurements(frame, pose())
    assert meas.position_m == pytest.approx([102.0, -20.0 + 0.9 + 1.5])
    # Across the beam (east here) the echo could be anywhere in the cone.
    assert meas.cov_m2[0, 0] > 2.0 * meas.cov_m2[1, 1]
    assert front_end.free_ranges_m(frame) == [4.0, 1.5]


def test_a_cam_reference_at_the_front_is_moved_back_to_the_rear_bumper():
    obs = V2vObservation(station_id=9, x_m=50.0, y_m=10.0, speed_mps=8.0, heading_rad=math.pi / 2,
                         accel_mps2=-1.0, length_m=4.0, width_m=1.8, sample_time_s=2.0)
    meas = V2vFrontEnd(V2vConfig(), RejectCounter()).measurement(obs, pose())
    assert meas.position_m == pytest.approx([50.0, 6.0])
    assert meas.velocity_mps == pytest.approx([0.0, 8.0], abs=1e-9)
    assert meas.time_s == 2.0 and meas.station_id == 9
    as_is = V2vFrontEnd(V2vConfig(reference_is_front=False), RejectCounter()).measurement(obs, pose())
    assert as_is.position_m == pytest.approx([50.0, 10.0])


def test_the_ego_pose_is_moved_along_its_arc_to_the_sensor_sample_time():
    ego = ego_pb2.EgoState(x_m=0.0, y_m=0.0, heading_rad=0.0, speed_mps=10.0, yaw_rate_radps=0.0)
    ego.header.sample_time_s = 1.0
    later = EgoPose.from_state(ego).at(1.1)
    assert later.x_m == pytest.approx(1.0)
    assert later.to_enu(10.0, 0.0) == pytest.approx([11.0, 0.0])


def test_a_nearest_point_beside_our_axis_is_a_rear_corner_and_moves_out_to_the_rear_centre():
    centre, lateral_std = nearest_point_to_rear_centre(12.0, 3.1, 1.8)
    assert centre == pytest.approx([12.0, 4.0])
    assert lateral_std == pytest.approx(0.45)
    straddling, wide_std = nearest_point_to_rear_centre(12.0, 0.2, 1.8)
    assert straddling == pytest.approx([12.0, 0.2])
    assert wide_std == pytest.approx(0.9)


def test_radar_speed_stays_along_the_beam_to_the_reflection_point_after_the_shift():
    frame = sensors_pb2.RadarTracks()
    frame.tracks.add(track_id=1, range_m=math.hypot(9.0, 3.1), azimuth_rad=math.atan2(3.1, 9.0), width_m=1.8)
    (meas,) = RadarFrontEnd(RadarConfig(), RejectCounter()).measurements(frame, pose(x_m=0.0, y_m=0.0))
    assert meas.position_m == pytest.approx([9.0, 4.0])
    assert meas.line_of_sight == pytest.approx(np.array([9.0, 3.1]) / math.hypot(9.0, 3.1))
