"""Plexe's CACC as the baseline of a string run: the scenario's platoon driven by SUMO's CC car-following model
(Plexe's controllers, MSCFModel_CC) in libsumo, in this process, beside our own run.

The leader drives the scenario leader's speed profile exactly (its speed set every step, as our simulator drives a
scripted leader); every follower runs Plexe's PLOEG controller (Ploeg et al. 2011), a time-gap policy like our CACC,
at the scenario's time gap, with SUMO's first-order engine lag set to the followers' driveline time constant and
their acceleration limits. Plexe's CACC (Rajamani's) is a constant-spacing policy and is not the like of ours.
Each follower gets its predecessor's requested acceleration, as in Plexe: the first follower from the leader (its
actual acceleration: the leader has no engine lag), the others from SUMO (Plexe's auto-feeding). SUMO steps at the
scenario's step; the string gain per pair is the judge's (services/sim/metrics.py), over the same window.
"""

from __future__ import annotations

import tempfile
from dataclasses import dataclass
from pathlib import Path

import numpy as np

from coopdrive.launch.plexe_files import (ROUTE_ID, SUMO_PLEXE, TYPE_ID, PlexeBaselineError, PlexeVehicleType,
                                          write_network, write_routes)
from coopdrive.services.sim.string_gain import judged_string_gains
from coopdrive.services.sim.scenario_config import ScenarioConfig
from coopdrive.services.sim.speed_profiles import SpeedProfile
from coopdrive.services.sim.sumo_routes import LIBSUMO_REQUIREMENT

# Plexe's controllers (CC_Const.h, ACTIVE_CONTROLLER): the leader is driven, the followers run Ploeg's CACC.
DRIVER, PLOEG = 0, 4
# Ploeg et al. (2011)'s gains, which SUMO's CC model takes by default too.
PLOEG_KP = 0.2
PLOEG_KD = 0.7
# Plexe's Ploeg controller keeps a fixed standstill gap of 2 m (MSCFModel_CC::_ploeg): its spacing is 2 m + h v.
PLEXE_STANDSTILL_M = 2.0
# libsumo hands a vehicle's parameters so prefixed to its car-following model (Plexe's keys, CC_Const.h).
CAR_FOLLOWING = "carFollowModel."
ACTIVE_CONTROLLER = CAR_FOLLOWING + "ccac"
DESIRED_SPEED = CAR_FOLLOWING + "ccds"
AUTO_FEEDING = CAR_FOLLOWING + "ccaf"
PREDECESSOR_DATA = CAR_FOLLOWING + "ccpsa"
# Road beyond the distance the platoon can cover in the run.
ROAD_MARGIN_M = 500.0


def sumo_library():
    """libsumo, or PlexeBaselineError naming it when it cannot be imported."""
    try:
        import libsumo
    except ImportError:
        raise PlexeBaselineError(f"--baseline {SUMO_PLEXE} needs libsumo, which is not installed "
                                 f"(pip install '{LIBSUMO_REQUIREMENT}')") from None
    return libsumo


@dataclass(frozen=True)
class PlexeString:
    """The platoon of a string scenario as SUMO drives it under Plexe's controllers."""

    vehicle_count: int
    leader_profile: SpeedProfile
    vehicle_type: PlexeVehicleType
    step_s: float
    duration_s: float
    seed: int
    string_start_s: float
    string_end_s: float
    string_frequency_hz: float | None

    @classmethod
    def of(cls, config: ScenarioConfig, duration_s: float | None = None, seed: int = 1) -> PlexeString:
        """The scenario's judged platoon: its scripted leader's profile, its first follower's vehicle."""
        platoon = config.judging.platoon
        vehicles = {vehicle.vehicle_id: vehicle for vehicle in config.vehicles}
        if len(platoon) < 2 or not all(vehicle_id in vehicles for vehicle_id in platoon):
            raise PlexeBaselineError(f"--baseline {SUMO_PLEXE}: scenario {config.name} judges no platoon of a leader "
                                     "and followers (judging.platoon)")
        leader = vehicles[platoon[0]]
        if leader.speed_profile is None:
            raise PlexeBaselineError(f"--baseline {SUMO_PLEXE}: the platoon's leader {leader.vehicle_id} of scenario "
                                     f"{config.name} drives no speed profile for Plexe's leader to drive")
        plant = vehicles[platoon[1]].plant_profile()
        vehicle_type = PlexeVehicleType(
            length_m=plant.length_m, max_accel_mps2=plant.max_accel_mps2, max_decel_mps2=plant.max_decel_mps2,
            max_speed_mps=plant.max_speed_mps, engine_tau_s=plant.response_time_constant_s,
            ploeg_h_s=config.judging.headway_s, ploeg_kp=PLOEG_KP, ploeg_kd=PLOEG_KD)
        judging = config.judging
        return cls(len(platoon), leader.speed_profile, vehicle_type, config.step_s, duration_s or config.duration_s,
                   seed, judging.string_start_s, judging.string_end_s, judging.string_frequency_hz)

    def description(self) -> str:
        kind = self.vehicle_type
        return (f"Plexe's PLOEG CACC in SUMO (h {kind.ploeg_h_s:g} s, kp {kind.ploeg_kp:g}, kd {kind.ploeg_kd:g}, "
                f"standstill {PLEXE_STANDSTILL_M:g} m, engine lag {kind.engine_tau_s:g} s)")

    def vehicle_ids(self) -> list[str]:
        return [f"plexe{index}" for index in range(self.vehicle_count)]

    def start_gap_m(self) -> float:
        """Plexe's PLOEG spacing at the leader's first speed: the platoon starts in equilibrium."""
        return PLEXE_STANDSTILL_M + self.vehicle_type.ploeg_h_s * self.leader_profile.speed_at(0.0)

    def road_length_m(self) -> float:
        platoon_m = self.vehicle_count * (self.vehicle_type.length_m + self.start_gap_m())
        return platoon_m + self.vehicle_type.max_speed_mps * self.duration_s + ROAD_MARGIN_M


@dataclass(frozen=True)
class PlexeRun:
    """Every vehicle's speed (rows, leader first) at each step's time."""

    time_s: np.ndarray
    speeds_mps: np.ndarray

    def metrics(self, setup: PlexeString) -> dict[str, float]:
        """string_gain and each pair's, as the judge measures ours."""
        return judged_string_gains(self.time_s, list(self.speeds_mps), setup.string_start_s, setup.string_end_s,
                                   setup.string_frequency_hz)


def run_plexe_string(setup: PlexeString) -> PlexeRun:
    """Drives the platoon in libsumo for the run's duration; SUMO is closed at the end."""
    libsumo = sumo_library()
    with tempfile.TemporaryDirectory(prefix="coopdrive-plexe-") as folder:
        network = write_network(Path(folder), setup.road_length_m(), setup.vehicle_type.max_speed_mps)
        routes = write_routes(Path(folder), setup.vehicle_type)
        libsumo.start(["sumo", "--net-file", str(network), "--route-files", str(routes), "--step-length",
                       str(setup.step_s), "--seed", str(setup.seed), "--xml-validation", "never", "--no-step-log",
                       "--no-warnings", "--collision.action", "none"])
        try:
            _add_platoon(libsumo, setup)
            return _drive(libsumo, setup)
        finally:
            libsumo.close()


def _add_platoon(sumo, setup: PlexeString) -> None:
    ids = setup.vehicle_ids()
    speed_mps = setup.leader_profile.speed_at(0.0)
    front_m = setup.road_length_m() - setup.vehicle_type.max_speed_mps * setup.duration_s - ROAD_MARGIN_M
    for index, vehicle_id in enumerate(ids):
        position_m = front_m - index * (setup.vehicle_type.length_m + setup.start_gap_m())
        sumo.vehicle.add(vehicle_id, ROUTE_ID, typeID=TYPE_ID, departPos=f"{position_m:.3f}",
                         departSpeed=f"{speed_mps:.3f}", departLane="0")
        # Speed mode 0: SUMO's own safe-speed checks off, the controller alone decides (as Plexe runs its cars).
        sumo.vehicle.setSpeedMode(vehicle_id, 0)
        sumo.vehicle.setParameter(vehicle_id, ACTIVE_CONTROLLER, str(DRIVER if index == 0 else PLOEG))
        sumo.vehicle.setParameter(vehicle_id, DESIRED_SPEED, str(setup.vehicle_type.max_speed_mps))
        if index >= 2:
            sumo.vehicle.setParameter(vehicle_id, AUTO_FEEDING, f"1:{ids[0]}:{ids[index - 1]}")


def _feed_first_follower(sumo, leader_id: str, follower_id: str, time_s: float) -> None:
    """The leader's data as Plexe's predecessor record (speed, acceleration, x, y, time, requested acceleration,
    velocity x, y, angle): the driven leader's requested acceleration is its acceleration."""
    x_m, y_m = sumo.vehicle.getPosition(leader_id)
    speed_mps, accel_mps2 = sumo.vehicle.getSpeed(leader_id), sumo.vehicle.getAcceleration(leader_id)
    record = (speed_mps, accel_mps2, x_m, y_m, time_s, accel_mps2, speed_mps, 0.0, 0.0)
    sumo.vehicle.setParameter(follower_id, PREDECESSOR_DATA, ":".join(f"{value:.6f}" for value in record))


def _drive(sumo, setup: PlexeString) -> PlexeRun:
    ids = setup.vehicle_ids()
    steps = int(round(setup.duration_s / setup.step_s))
    time_s = np.arange(steps + 1) * setup.step_s
    speeds = np.empty((len(ids), steps + 1))
    speeds[:, 0] = setup.leader_profile.speed_at(0.0)
    for step in range(1, steps + 1):
        _feed_first_follower(sumo, ids[0], ids[1], time_s[step - 1])
        sumo.vehicle.setSpeed(ids[0], setup.leader_profile.speed_at(time_s[step]))
        sumo.simulationStep()
        speeds[:, step] = [sumo.vehicle.getSpeed(vehicle_id) for vehicle_id in ids]
    return PlexeRun(time_s, speeds)
