import pytest

from coopdrive.services.sim.participants import EmergencyVehicle, IntentKind, ScriptedVehicle
from coopdrive.services.sim.profiles import PASSENGER_CAR
from coopdrive.services.sim.road_geometry import straight_road
from coopdrive.services.sim.roadside_unit import RoadsideUnit, RsuEvent, RsuEventKind
from coopdrive.services.sim.speed_profiles import LaneChange, PiecewiseSpeed, SinusoidSpeed, SpeedPoint


def test_a_piecewise_profile_interpolates_and_holds_its_ends():
    profile = PiecewiseSpeed(points=[SpeedPoint(time_s=10.0, speed_mps=22.2), SpeedPoint(time_s=20.0, speed_mps=11.1)])
    assert [profile.speed_at(t) for t in (0.0, 15.0, 30.0)] == pytest.approx([22.2, 16.65, 11.1])


def test_a_sinusoid_profile_starts_at_start_time_and_stops_after_its_periods():
    profile = SinusoidSpeed(mean_speed_mps=20.0, amplitude_mps=2.78, frequency_hz=0.2, start_s=5.0, periods=2)
    assert profile.speed_at(4.0) == 20.0
    assert profile.speed_at(5.0 + 1.25) == pytest.approx(22.78)
    assert profile.speed_at(16.0) == 20.0


def test_a_scripted_vehicle_drives_its_profile_and_changes_lane_smoothly():
    lanes = straight_road(2)
    car = ScriptedVehicle("x", 7, PASSENGER_CAR, lanes, lane_index=1, station_m=100.0,
                          speed_profile=PiecewiseSpeed(points=[SpeedPoint(time_s=0.0, speed_mps=10.0)]),
                          lane_changes=[LaneChange(start_s=2.0, target_lane=0, duration_s=4.0)])
    ys, headings = [], []
    for k in range(1, 101):
        truth = car.step(k * 0.1)
        ys.append(truth.y_m)
        headings.append(truth.heading_rad)
    assert truth.x_m == pytest.approx(200.0)
    assert truth.y_m == pytest.approx(0.0, abs=1e-9) and truth.lane_index == 0
    assert all(b <= a + 1e-9 for a, b in zip(ys, ys[1:]))
    assert min(headings) < -0.05 and abs(headings[-1]) < 1e-9
    assert max(abs(b - a) for a, b in zip(ys, ys[1:])) < 0.2


def test_scripted_vehicles_send_cams_at_their_rate_and_the_rude_one_is_marked():
    car = ScriptedVehicle("rude", 9, PASSENGER_CAR, straight_road(1), 0, 0.0, ignores_protocol=True)
    intents = [i for k in range(100) for i in car.messages_due(k * 0.01)]
    assert len(intents) == 25 and all(i.kind is IntentKind.CAM for i in intents)
    assert car.ignores_protocol


def test_an_emergency_vehicle_announces_itself_while_its_siren_is_on():
    ev = EmergencyVehicle("ev", 99, PASSENGER_CAR, straight_road(2), 0, 0.0, lateral_offset_m=1.75,
                          siren_on_s=1.0, siren_off_s=2.0)
    assert ev.step(0.5).y_m == pytest.approx(1.75)
    assert [i.kind for i in ev.messages_due(0.5)] == [IntentKind.CAM]
    kinds = [i.kind for i in ev.messages_due(1.5)]
    assert kinds == [IntentKind.CAM, IntentKind.DENM]


def test_the_roadside_unit_starts_the_platoon_and_announces_road_works_from_their_times():
    rsu = RoadsideUnit("rsu", 1000, 0.0, 0.0, [
        RsuEvent(kind=RsuEventKind.START_PLATOON, time_s=1.0, until_s=3.0),
        RsuEvent(kind=RsuEventKind.ROADWORKS, time_s=2.0, x_m=500.0, closed_lane=1)])
    assert rsu.messages_due(0.5) == []
    assert [i.fields for i in rsu.messages_due(1.0)] == [{"start_platoon": 0}]
    kinds = sorted(i.kind.value for i in rsu.messages_due(2.5))
    assert kinds == ["denm", "iclcm"]
    assert [i.kind for i in rsu.messages_due(3.5)] == [IntentKind.DENM]


def test_road_works_stay_valid_for_as_long_as_they_last_so_no_repetition_expires():
    rsu = RoadsideUnit("rsu", 1000, 0.0, 0.0, [
        RsuEvent(kind=RsuEventKind.ROADWORKS, time_s=2.0, x_m=500.0),
        RsuEvent(kind=RsuEventKind.ROADWORKS, time_s=2.0, until_s=62.0, x_m=900.0)])
    validities = [i.fields["validity_s"] for i in rsu.messages_due(3.0)]
    assert validities == [86400.0, 60.0]


def test_a_scripted_car_slows_behind_a_slower_car_in_its_path_instead_of_driving_into_it():
    lanes = straight_road(2)
    fast = ScriptedVehicle("fast", 7, PASSENGER_CAR, lanes, lane_index=0, station_m=0.0,
                           speed_profile=PiecewiseSpeed(points=[SpeedPoint(time_s=0.0, speed_mps=16.7)]))
    slow = ScriptedVehicle("slow", 8, PASSENGER_CAR, lanes, lane_index=0, station_m=60.0,
                           speed_profile=PiecewiseSpeed(points=[SpeedPoint(time_s=0.0, speed_mps=11.1)]))
    beside = ScriptedVehicle("beside", 9, PASSENGER_CAR, lanes, lane_index=1, station_m=30.0,
                             speed_profile=PiecewiseSpeed(points=[SpeedPoint(time_s=0.0, speed_mps=5.0)]))
    gaps = []
    for k in range(1, 1501):
        others = [slow.truth(), beside.truth()]
        truth = fast.step(k * 0.02, others)
        slow.step(k * 0.02)
        beside.step(k * 0.02)
        gaps.append(slow.truth().x_m - truth.x_m)
    assert min(gaps) > 4.5 + 4.0
    assert truth.speed_mps == pytest.approx(11.1, abs=0.3)


def test_a_scripted_car_with_nobody_in_its_path_keeps_its_profile_exactly():
    lanes = straight_road(2)
    car = ScriptedVehicle("x", 7, PASSENGER_CAR, lanes, lane_index=0, station_m=0.0,
                          speed_profile=PiecewiseSpeed(points=[SpeedPoint(time_s=0.0, speed_mps=10.0),
                                                               SpeedPoint(time_s=1.0, speed_mps=20.0)]))
    beside = ScriptedVehicle("beside", 9, PASSENGER_CAR, lanes, lane_index=1, station_m=10.0)
    for k in range(1, 101):
        truth = car.step(k * 0.02, [beside.truth()])
    assert truth.speed_mps == pytest.approx(20.0)
    assert truth.x_m == pytest.approx(15.0 + 20.0, abs=0.01)
