"""Vehicle profiles for the control laws: the vehicle's description (coopdrive/vehicle, the one the simulator and
geolocation read too), the limits control keeps to and the laws' gains.

Every field carries its unit. Gains named after the equation they belong to; the defaults of the
reference laws are the published ones (Ploeg kp = 0.2, kd = 0.7; Rajamani lambda = 0.1; DRIVERTIVE
Table II), ours were tuned with `string_stability.py` (see docs in that module).
"""

from __future__ import annotations

from pydantic import BaseModel, ConfigDict, Field

from coopdrive.vehicle import PASSENGER_CAR, SPACING, VehicleDescription, VehicleKind
from coopdrive.vehicle import TRUCK as TRUCK_VEHICLE

class _Model(BaseModel):
    model_config = ConfigDict(extra="forbid", frozen=True)


class CaccGains(_Model):
    """Our CACC: u = FF(a_p or the request u_p) + filtered (kp e + kd de/dt), e = gap - (r + h v)."""

    kp_1ps2: float = Field(0.2, gt=0)
    kd_1ps: float = Field(2.5, gt=0)
    # The PD output's first-order filter (0 = none): kd would pass the speed noise in e' straight through.
    feedback_time_constant_s: float = Field(0.2, ge=0)
    # Bumpless transfer: the offset between the previous command and this law decays with this constant.
    bump_time_constant_s: float = Field(1.0, gt=0)
    # How far the request feed-forward leads to make up for the request's age theta at our control (eq. C5;
    # 0 = none): in the simulated platoons the predecessor's iCLCM request is in our scene 0.10 s after it was
    # made (V2V at 25 Hz, the sender's and our pipelines), and our 50 Hz control reads that 25 Hz scene up to a
    # period later: 0.11-0.12 s in all (string, seeds 1-3, every pair). At the wave frequencies the string gain
    # weighs the feed-forward's phase, not its size (eq. SS2), so each 0.01 s of age left uncompensated adds about
    # 0.006 to the 0.2 Hz gain: 0.1 s left the string 0.01 above the ideal 1 / |1 + h s|.
    request_lead_s: float = Field(0.12, ge=0)


class PloegGains(_Model):
    kp_1ps2: float = Field(0.2, gt=0)
    kd_1ps: float = Field(0.7, gt=0)


class AccGains(_Model):
    """Our radar-only ACC: u = kv (v_p - v) + ke (gap - r - h v) - ka h a."""

    kv_1ps: float = Field(1.0, gt=0)
    ke_1ps2: float = Field(0.15, gt=0)
    ka: float = Field(0.2, ge=0)


class RajamaniGains(_Model):
    lambda_1ps: float = Field(0.1, gt=0)


class CruiseGains(_Model):
    """Cruise PI (Heudiasyc eq. 3 structure) on a reference-model speed."""

    kp_1ps: float = Field(0.8, gt=0)
    ki_1ps2: float = Field(0.15, ge=0)
    # Back-calculation anti-windup: how fast the integrator follows the applied command.
    tracking_time_constant_s: float = Field(1.0, gt=0)
    # Reference model: first-order approach to the desired speed with bounded accel and jerk.
    reference_time_constant_s: float = Field(3.0, gt=0)
    reference_accel_mps2: float = Field(1.5, gt=0)
    reference_decel_mps2: float = Field(1.5, gt=0)
    reference_jerk_mps3: float = Field(1.0, gt=0)
    # While another law follows a target, the set speed is enforced by a governor this quick (eq. S4).
    governor_time_constant_s: float = Field(1.0, gt=0)
    resistance_feedforward: bool = True


class DrivertiveGains(_Model):
    """DRIVERTIVE adaptive proportional speed law (eq. 4-5, Table II), output read as m/s2."""

    k0_1ps: float = 0.2
    kv0_1pm: float = 0.04
    k1_1ps: float = 1.0
    kv1_1pm: float = 0.0


class DcaccGains(_Model):
    # Least-squares slope of the predecessor speed over this window estimates its acceleration.
    estimator_window_s: float = Field(0.4, gt=0)
    estimator_min_samples: int = Field(5, ge=3)


class SpacingDefaults(_Model):
    """The planner requests the gap (coopdrive/vehicle/spacing.py's policy, where it gives none); these are how
    this vehicle's control degrades it."""

    # V2V older than this is lost (GCDC: a station not heard for 400 ms is lost).
    v2v_timeout_s: float = Field(0.4, gt=0)
    dcacc_time_gap_s: float = Field(SPACING.dcacc_time_gap_s, gt=0)
    acc_time_gap_s: float = Field(SPACING.acc_time_gap_s, gt=0)
    # Added to the planner's time gap on fallback, then floored by the values above.
    fallback_time_gap_raise_s: float = Field(0.3, ge=0)
    time_gap_rate_sps: float = Field(0.2, gt=0)


class LimitGains(_Model):
    max_accel_mps2: float = Field(2.0, gt=0)
    max_decel_mps2: float = Field(2.0, gt=0)
    max_jerk_mps3: float = Field(2.5, gt=0)
    emergency_decel_mps2: float = Field(6.0, gt=0)
    emergency_jerk_mps3: float = Field(30.0, gt=0)
    # Emergency braking triggers below this time to collision, or when braking at the comfort decel would let the
    # gap fall below the stop margin within the horizon; it releases with release_margin_m to spare.
    ttc_emergency_s: float = Field(1.5, gt=0)
    ttc_release_s: float = Field(3.0, gt=0)
    brake_horizon_s: float = Field(2.5, gt=0)
    # A predecessor decelerating this hard is braking in earnest (the EEBL trigger of 4 m/s2): match it at once.
    hard_braking_mps2: float = Field(4.0, gt=0)
    stop_margin_m: float = Field(2.0, ge=0)
    release_margin_m: float = Field(1.0, ge=0)


class LateralGains(_Model):
    # Heudiasyc eq. 10: critically damped double integrator, alpha1 = wn^2, alpha2 = 2 wn.
    alpha1_1ps2: float = Field(0.36, gt=0)
    alpha2_1ps: float = Field(1.2, gt=0)
    stanley_gain: float = Field(1.0, gt=0)
    stanley_softening_mps: float = Field(1.0, gt=0)
    pure_pursuit_lookahead_time_s: float = Field(1.5, gt=0)
    pure_pursuit_min_lookahead_m: float = Field(5.0, gt=0)
    # Below this speed the L / v^2 factor of eq. 10 is evaluated at this speed (singularity at standstill).
    min_speed_mps: float = Field(2.0, gt=0)
    lane_change_duration_s: float = Field(6.0, gt=0)


class SteeringLimits(_Model):
    """What control commands at most: inside the steering's mechanical limits (the vehicle's description)."""

    max_angle_rad: float = Field(gt=0)
    max_rate_radps: float = Field(gt=0)
    max_lateral_accel_mps2: float = Field(2.0, gt=0)


class VehicleProfile(_Model):
    # "car" or "truck": what `coopdrive analyze string --profile` names.
    name: str
    vehicle: VehicleDescription
    steering: SteeringLimits
    cacc: CaccGains = CaccGains()
    ploeg: PloegGains = PloegGains()
    acc: AccGains = AccGains()
    rajamani: RajamaniGains = RajamaniGains()
    cruise: CruiseGains = CruiseGains()
    drivertive: DrivertiveGains = DrivertiveGains()
    dcacc: DcaccGains = DcaccGains()
    spacing: SpacingDefaults = SpacingDefaults()
    limits: LimitGains = LimitGains()
    lateral: LateralGains = LateralGains()

    @property
    def wheelbase_m(self) -> float:
        return self.vehicle.wheelbase_m

    @property
    def engine_lag_s(self) -> float:
        """The driveline's first-order lag (iCLCM responseTimeConstant), which the laws compensate."""
        return self.vehicle.response_time_constant_s

    @property
    def actuation_delay_s(self) -> float:
        """The driveline's dead time (iCLCM responseTimeDelay)."""
        return self.vehicle.response_dead_time_s

    def resistance_accel_mps2(self, speed_mps: float) -> float:
        return self.vehicle.resistance_accel_mps2(speed_mps)

    def with_driveline(self, lag_s: float | None = None, dead_time_s: float | None = None) -> VehicleProfile:
        """This profile on a vehicle whose driveline lags lag_s with dead_time_s (None: as described)."""
        update = {"response_time_constant_s": lag_s, "response_dead_time_s": dead_time_s}
        vehicle = self.vehicle.model_copy(update={k: v for k, v in update.items() if v is not None})
        return self.model_copy(update={"vehicle": vehicle})


CAR = VehicleProfile(name="car", vehicle=PASSENGER_CAR, steering=SteeringLimits(max_angle_rad=0.5, max_rate_radps=0.4))

TRUCK = VehicleProfile(
    name="truck",
    vehicle=TRUCK_VEHICLE,
    steering=SteeringLimits(max_angle_rad=0.6, max_rate_radps=0.25),
    spacing=SpacingDefaults(dcacc_time_gap_s=1.3, acc_time_gap_s=2.0),
    limits=LimitGains(max_accel_mps2=1.0, max_decel_mps2=2.0, max_jerk_mps3=1.5, emergency_decel_mps2=4.5),
)

PROFILES: dict[VehicleKind, VehicleProfile] = {profile.vehicle.kind: profile for profile in (CAR, TRUCK)}


def profile_by_name(name: str) -> VehicleProfile:
    """By its name ("car", "truck") or its vehicle's kind ("passenger_car")."""
    for profile in PROFILES.values():
        if name in (profile.name, profile.vehicle.kind.value):
            return profile
    known = sorted(p.name for p in PROFILES.values())
    raise ValueError(f"unknown vehicle profile {name!r}; known: {known}") from None
