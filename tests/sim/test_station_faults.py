"""Station faults in what participants broadcast: a ghost vehicle's CAMs and a station's offset CAMs."""

import math

import pytest

from coopdrive.services.sim.fault_config import GhostVehicle, PositionOffset
from coopdrive.services.sim.participants import IntentKind, MessageIntent
from coopdrive.services.sim.station_faults import StationFaults, ghost_sender
from coopdrive.v1 import sim_pb2

TARGET = sim_pb2.VehicleTruth(vehicle_id="a1", x_m=100.0, y_m=50.0, heading_rad=math.pi / 2, speed_mps=20.0,
                              length_m=4.5, width_m=1.8, lane_index=0)


def cam(sender_id="car", x_m=10.0, y_m=20.0):
    return MessageIntent(IntentKind.CAM, sender_id, 7, 1.0, {"x_m": x_m, "y_m": y_m})


def test_a_ghost_sends_cams_claiming_a_car_ahead_of_its_target_at_its_speed_while_the_fault_lasts():
    ghost = GhostVehicle(type="ghost_vehicle", vehicle_id="a1", start_s=1.0, end_s=2.0, gap_m=20.0, rate_hz=10.0)
    faults = StationFaults([ghost])
    assert faults.apply([], 0.5, [TARGET]) == []
    (intent,) = faults.apply([], 1.0, [TARGET])
    assert (intent.sender_id, intent.station_id, intent.fields["speed_mps"]) == (ghost_sender(ghost), 999_001, 20.0)
    # Heading north: the ghost is straight ahead, past the target's front bumper, the gap and its own overhang.
    assert intent.fields["x_m"] == pytest.approx(100.0)
    assert intent.fields["y_m"] > 50.0 + 20.0
    assert faults.positions(1.0, [TARGET])[ghost_sender(ghost)] == pytest.approx((intent.fields["x_m"],
                                                                                 intent.fields["y_m"]))
    assert faults.apply([], 1.05, [TARGET]) == []  # 10 Hz
    assert len(faults.apply([], 1.1, [TARGET])) == 1
    assert faults.apply([], 2.0, [TARGET]) == [] and faults.positions(2.0, [TARGET]) == {}


def test_an_offset_station_s_cams_are_shifted_and_others_are_not():
    faults = StationFaults([PositionOffset(type="position_offset", vehicle_id="car", start_s=0.0, east_m=5.0,
                                           north_m=-2.0)])
    shifted, other = faults.apply([cam("car"), cam("other")], 1.0, [])
    assert (shifted.fields["x_m"], shifted.fields["y_m"]) == (15.0, 18.0)
    assert (other.fields["x_m"], other.fields["y_m"]) == (10.0, 20.0)
