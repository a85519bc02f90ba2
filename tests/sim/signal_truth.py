"""Ground truth of one car on the x axis approaching one signalised stop line at x = 0, for the judges of
signalised intersections (signal_metrics.py, signal_fault_reactions.py)."""

import math

from coopdrive.messages.vehicle_frame import rear_overhang_m
from coopdrive.v1 import infrastructure_pb2 as pb
from coopdrive.v1 import sim_pb2

SAMPLE_S = 0.1
INTERSECTION_ID = 7
LENGTH_M = 4.5
FRONT_M = LENGTH_M - rear_overhang_m(LENGTH_M)
GREEN, AMBER, RED, RED_AMBER = (pb.MOVEMENT_PHASE_STATE_PROTECTED_MOVEMENT_ALLOWED,
                                pb.MOVEMENT_PHASE_STATE_PROTECTED_CLEARANCE, pb.MOVEMENT_PHASE_STATE_STOP_AND_REMAIN,
                                pb.MOVEMENT_PHASE_STATE_PRE_MOVEMENT)


def light(phases, intersection_id=INTERSECTION_ID):
    """phases: (state, start_s, end_s) in order; the last amber's end is the next red."""
    def at(time_s):
        state, _, end_s = next(p for p in phases if time_s < p[2])
        amber_end_s = next((e for s, b, e in phases if s == AMBER and e > time_s), math.inf)
        amber_end_s = time_s if state == RED else amber_end_s
        return sim_pb2.SignalTruth(intersection_id=intersection_id, signal_group=2, state=state, phase_end_s=end_s,
                                   amber_end_s=amber_end_s, stop_x_m=0.0, stop_y_m=0.0, heading_rad=0.0,
                                   lane_width_m=3.5)
    return at


def frames(front_of_time, light_at, until_s, vehicle_id="car1", start_s=0.0):
    """A car along the x axis whose front bumper is at front_of_time(t) (x, speed)."""
    result = []
    for k in range(round((until_s - start_s) / SAMPLE_S) + 1):
        time_s = start_s + k * SAMPLE_S
        front_m, speed_mps = front_of_time(time_s)
        car = sim_pb2.VehicleTruth(vehicle_id=vehicle_id, x_m=front_m - FRONT_M, y_m=-0.2, heading_rad=0.0,
                                   speed_mps=speed_mps, length_m=LENGTH_M, width_m=1.8)
        result.append((time_s, [car], [light_at(time_s)]))
    return result


def steady(speed_mps, crossing_s):
    return lambda t: (speed_mps * (t - crossing_s), speed_mps)
