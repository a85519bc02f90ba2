"""The simulated plant of each vehicle: its description (coopdrive/vehicle) as the simulator's vehicle model reads
it, with the deliberate differences between that description and the simulated vehicle (PlantPerturbation).

The stack's controllers know the vehicle by its description; a plant identical to it would test them against a
world that obeys their model exactly. The perturbations say where, and by how much, the simulated vehicle does not.
"""
from __future__ import annotations

from pydantic import BaseModel, ConfigDict, Field

from coopdrive.vehicle import PASSENGER_CAR as CAR_DESCRIPTION
from coopdrive.vehicle import TRUCK as TRUCK_DESCRIPTION
from coopdrive.vehicle import VehicleDescription, VehicleKind

STANDARD_GRAVITY_MPS2 = 9.80665


class _Frozen(BaseModel):
    model_config = ConfigDict(extra="forbid", frozen=True)


class PlantPerturbation(_Frozen):
    """Where the simulated vehicle differs from its description on purpose (None: as described)."""

    # The driveline responds slower than the vehicle announces and its control laws compensate for.
    response_time_constant_s: float | None = Field(default=None, gt=0)
    response_dead_time_s: float | None = Field(default=None, ge=0)
    # The true driving resistance, which the controllers' feed-forward only estimates.
    drag_area_m2: float | None = Field(default=None, gt=0)
    rolling_coefficient: float | None = Field(default=None, ge=0)
    # The air the plant drives through: warmer than the ISA air the feed-forward assumes.
    air_density_kgpm3: float = Field(default=1.2, gt=0)


# The car's driveline is 0.2 s slower and its dead time twice what its controllers assume, its c_d A 7 % lower and
# its rolling coefficient 8 % higher; the truck's slow engine and air brakes lag 0.8 s with 0.3 s dead time
# against the 0.5 s and 0.1 s it announces.
PLANT_PERTURBATIONS: dict[VehicleKind, PlantPerturbation] = {
    VehicleKind.PASSENGER_CAR: PlantPerturbation(response_time_constant_s=0.5, response_dead_time_s=0.1,
                                                 drag_area_m2=0.65, rolling_coefficient=0.013),
    VehicleKind.TRUCK: PlantPerturbation(response_time_constant_s=0.8, response_dead_time_s=0.3),
}


def rolling_resistance_mps2(rolling_coefficient: float) -> float:
    """Rolling resistance as a deceleration: c_r g."""
    return rolling_coefficient * STANDARD_GRAVITY_MPS2


def drag_1pm(drag_area_m2: float, mass_kg: float, air_density_kgpm3: float) -> float:
    """Aerodynamic drag as a deceleration per speed squared: rho c_d A / (2 m)."""
    return 0.5 * air_density_kgpm3 * drag_area_m2 / mass_kg


class VehicleProfile(VehicleDescription):
    """The plant: the vehicle's description with its perturbations applied (built by plant_profile), and its
    driving resistance as the vehicle model steps it: a_res = rolling + drag v^2 (0 = an ideal actuator)."""

    rolling_resistance_mps2: float = Field(default=0.0, ge=0)
    drag_1pm: float = Field(default=0.0, ge=0)


def plant_profile(vehicle: VehicleDescription, perturbation: PlantPerturbation) -> VehicleProfile:
    """The simulated vehicle: its description, perturbed."""
    perturbed = perturbation.model_dump(exclude={"air_density_kgpm3"}, exclude_none=True)
    fields = {**dict(vehicle), **perturbed}
    return VehicleProfile(**fields, rolling_resistance_mps2=rolling_resistance_mps2(fields["rolling_coefficient"]),
                          drag_1pm=drag_1pm(fields["drag_area_m2"], vehicle.mass_kg, perturbation.air_density_kgpm3))


PASSENGER_CAR = plant_profile(CAR_DESCRIPTION, PLANT_PERTURBATIONS[VehicleKind.PASSENGER_CAR])
TRUCK = plant_profile(TRUCK_DESCRIPTION, PLANT_PERTURBATIONS[VehicleKind.TRUCK])
PROFILES: dict[VehicleKind, VehicleProfile] = {VehicleKind.PASSENGER_CAR: PASSENGER_CAR, VehicleKind.TRUCK: TRUCK}
