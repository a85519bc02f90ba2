"""Acceptance on a real car: 20 s of a 2017 RAV4's powertrain bus (comma2k19) through the shipped adapter
deploy/vehicles/toyota_rav4_2017.yaml and its opendbc DBC, against the values comma decoded from the same frames.

Measured (see docs/how-to/vehicle-can.md): without GNSS the service reports the wheels' speed and the yaw-rate
sensor as they arrive; dead reckoning from one fix, the filter's speed is within 0.031 m/s RMS of the mean wheel
speed and its yaw rate within 0.0013 rad/s RMS of KINEMATICS' YAW_RATE.
"""

import can
import numpy as np
import pytest

from coopdrive.can.adapter import load_adapter
from coopdrive.can.bus_reader import VehicleBusReader
from coopdrive.v1 import ego_pb2
from tests.can.rav4_drive import (
    RAV4_ADAPTER, ground_truth, held, kinematics_yaw_rate_radps, rav4_frames, rms, run_geolocation,
)

WHEEL_TRUTH = "comma2k19_ground_truth_wheel_speed_first20s.csv"
STEERING_TRUTH = "comma2k19_ground_truth_steering_angle_first20s.csv"
SPEED_RMS_LIMIT_MPS = 0.05
# KINEMATICS.YAW_RATE comes in 0.244 deg/s steps (0.0043 rad/s): the filter must stay within about one.
YAW_RATE_RMS_LIMIT_RADPS = 0.005
WHEEL_SPEEDS_ID, SPEED_ID = 0x0AA, 0x0B4


@pytest.fixture(scope="module")
def without_gnss():
    return run_geolocation(rav4_frames())


@pytest.fixture(scope="module")
def from_one_fix():
    first_speed_mps = float(ground_truth(WHEEL_TRUTH)["speed_mps"][0])
    return run_geolocation(rav4_frames(), first_fix_speed_mps=first_speed_mps)


def speed_and_yaw_rate_errors(run) -> tuple[np.ndarray, np.ndarray]:
    wheels = ground_truth(WHEEL_TRUTH)
    times_s, speed_mps = run.series("speed_mps")
    moving = times_s >= wheels["t_s"][0]
    speed_error = speed_mps[moving] - np.interp(times_s[moving], wheels["t_s"], wheels["speed_mps"])
    yaw_times_s, yaw_rate_radps = kinematics_yaw_rate_radps()
    times_s, estimate = run.series("yaw_rate_radps")
    sensed = times_s >= yaw_times_s[0]
    yaw_error = estimate[sensed] - np.interp(times_s[sensed], yaw_times_s, yaw_rate_radps)
    return speed_error, yaw_error


def test_the_rav4_adapter_loads_with_its_dbc_and_says_where_the_yaw_rate_sensor_is():
    adapter, database = load_adapter(RAV4_ADAPTER)
    assert adapter.has_yaw_rate_sensor and adapter.quantities["yaw_rate"].message == "KINEMATICS"
    assert database.get_message_by_name("WHEEL_SPEEDS").frame_id == WHEEL_SPEEDS_ID
    assert adapter.odometry.speed_wheels == "all" and not adapter.odometry.yaw_rate_from_wheels


def test_the_steering_wheel_angle_through_the_adapter_is_the_angle_comma_decoded():
    states = []
    reader = VehicleBusReader(on_vehicle_state=states.append, vehicle_can=RAV4_ADAPTER)
    for frame in rav4_frames():
        reader.feed(frame)
    truth = ground_truth(STEERING_TRUTH)
    times_s = np.array([s.header.sample_time_s for s in states])
    angle_deg = np.degrees([s.steering_wheel_angle_rad for s in states])
    error_deg = angle_deg - held(times_s, truth["t_s"], truth["steering_angle_deg"])
    assert len(states) > 1600
    assert np.max(np.abs(error_deg)) < 1e-6
    # The road-wheel angle is the steering-wheel angle over the adapter's ratio.
    assert states[-1].steering_angle_rad == pytest.approx(states[-1].steering_wheel_angle_rad / 16.88)


def test_without_gnss_geolocation_reports_the_car_s_speed_and_yaw_rate_and_no_position(without_gnss):
    speed_error, yaw_error = speed_and_yaw_rate_errors(without_gnss)
    assert rms(speed_error) < SPEED_RMS_LIMIT_MPS
    assert rms(yaw_error) < YAW_RATE_RMS_LIMIT_RADPS
    last = without_gnss.states[-1]
    assert last.mode == ego_pb2.LOCALISATION_MODE_LOST
    assert not last.covariance and last.speed_mps > 18.0


def test_dead_reckoning_from_one_fix_the_filter_follows_the_mean_wheel_speed_and_the_yaw_rate_sensor(from_one_fix):
    speed_error, yaw_error = speed_and_yaw_rate_errors(from_one_fix)
    assert len(speed_error) > 900
    assert rms(speed_error) < SPEED_RMS_LIMIT_MPS
    assert rms(yaw_error) < YAW_RATE_RMS_LIMIT_RADPS
    assert from_one_fix.counters["accepted_yaw_rate"] > 1600
    assert from_one_fix.states[-1].covariance


def test_frames_the_rav4_adapter_does_not_use_are_counted_once_as_ignored_and_none_is_rejected(without_gnss):
    counters = without_gnss.counters
    # 90 ids on this bus, 9 of them used (wheel speeds, speed, steering, kinematics, accelerometer, pedals,
    # gear, blinkers).
    assert counters["can_ids_ignored"] == 81
    assert counters["can_frames_received"] + counters["can_frames_ignored"] == len(rav4_frames())
    assert not [name for name in counters if name.startswith("can_rejected")]


def test_unknown_and_malformed_frames_among_the_rav4_s_are_counted_by_reason_and_the_speed_goes_on():
    frames = list(rav4_frames()[:3000])
    start_s = frames[0].timestamp
    wheel = next(f for f in frames if f.arbitration_id == WHEEL_SPEEDS_ID)
    speed = next(f for f in frames if f.arbitration_id == SPEED_ID)
    bad_checksum = bytearray(speed.data)
    bad_checksum[-1] ^= 0x5A
    junk = [can.Message(timestamp=start_s + 0.5, arbitration_id=WHEEL_SPEEDS_ID, data=wheel.data[:5],
                        is_extended_id=False),
            can.Message(timestamp=start_s + 0.6, arbitration_id=SPEED_ID, data=bytes(bad_checksum),
                        is_extended_id=False),
            can.Message(timestamp=start_s + 0.7, is_error_frame=True),
            can.Message(timestamp=start_s + 0.8, arbitration_id=0x1ABCDEF0, data=b"\xff" * 8),
            can.Message(timestamp=start_s + 0.9, arbitration_id=0x7FF, data=b"")]
    run = run_geolocation(sorted(frames + junk, key=lambda m: m.timestamp))
    counters = run.counters
    assert counters["can_rejected_wrong_length"] == 1
    assert counters["can_rejected_bad_checksum"] == 1
    assert counters["can_error_frames"] == 1
    adapter, database = load_adapter(RAV4_ADAPTER)
    used = {database.get_message_by_name(m).frame_id
            for m in [q.message for q in adapter.quantities.values()] + [adapter.gear.message]}
    assert counters["can_ids_ignored"] == len({f.arbitration_id for f in frames} - used) + 2
    assert run.states[-1].speed_mps > 8.0
