"""What each stack vehicle's services must know of its own vehicle in a scenario-file run.

The simulator's stack_overrides() hold what every stack shares (the map, the sensor mounting); this adds
what differs per vehicle: its ITS station id and MAC, its radio box's ports, its size, its platoon.
"""

from __future__ import annotations

from coopdrive.services.actuation.config import CAR_PEDAL_PROFILE, TRUCK_PEDAL_PROFILE
from coopdrive.services.sim.intent_encoder import WORLD_V2X_PROFILE
from coopdrive.services.sim.radio_box import RadioPorts
from coopdrive.services.sim.scenario_builder import speed_profile_of
from coopdrive.services.sim.scenario_config import ScenarioConfig, VehicleRole
from coopdrive.services.sim.sensor_config import GnssConfig
from coopdrive.services.sim.sensor_timing import mean_latency_s
from coopdrive.vehicle import VehicleKind, vehicle_of

MIN_CRUISE_SPEED_MPS = 5.0
PROFILE_SAMPLE_S = 0.1
# Time constants for a first-order lag to fall below ~2 % of where it started.
BRAKE_RELEASE_TIME_CONSTANTS = 4.0
# ... and to come within 5 % of a step.
STEERING_RESPONSE_TIME_CONSTANTS = 3.0
STATION_TYPE = {VehicleKind.PASSENGER_CAR: "passenger_car", VehicleKind.TRUCK: "heavy_truck"}


def station_mac(station_id: int) -> str:
    """A locally administered unicast MAC that carries the station id, so captures show who sent what."""
    octets = [0x02, 0x00] + list(station_id.to_bytes(4, "big"))
    return ":".join(f"{octet:02x}" for octet in octets)


def fastest_traffic_mps(config: ScenarioConfig) -> float:
    """The top speed any vehicle but an emergency vehicle reaches in the run (speed profiles sampled), so a
    stack's own cruise speed never caps it below the leader it follows."""
    steps = int(config.duration_s / PROFILE_SAMPLE_S) + 1
    return max((speed_profile_of(v).speed_at(k * PROFILE_SAMPLE_S) for v in config.vehicles
                if v.role is not VehicleRole.EMERGENCY for k in range(steps)), default=0.0)


def _receiver_errors(gnss: GnssConfig) -> dict[str, float]:
    """What the stack is told of its receiver beyond the geolocator's defaults: a receiver with white errors (the
    ideal world's) has no correlated error to model, and one with a fixed latency stamps its fixes exactly."""
    errors = {}
    if gnss.error_correlation_time_s == 0.0:
        errors["gnss_error_std_m"] = 0.0
    if gnss.timing.latency_jitter_s == 0.0:
        errors["gnss_time_error_std_s"] = 0.0
    return errors


def vehicle_overrides(config: ScenarioConfig, vehicle_id: str, radio: RadioPorts | None) -> dict[str, dict]:
    vehicle = next(v for v in config.vehicles if v.vehicle_id == vehicle_id)
    # The vehicle's one description: every service that needs its geometry or dynamics is told which vehicle it is.
    description = vehicle_of(vehicle.profile)
    v2x: dict = {
        "profile": WORLD_V2X_PROFILE.value,
        "station_id": vehicle.station_id,
        "vehicle_mac": station_mac(vehicle.station_id),
        "station_type": STATION_TYPE[vehicle.profile],
        "clock_epoch_utc": config.utc_epoch.isoformat(),
        "vehicle": {"length_m": description.length_m, "width_m": description.width_m,
                    "rear_axle_location_m": description.front_bumper_x_m},
    }
    if radio is not None:
        v2x["link"] = {"radio_port": radio.box_port, "listen_port": radio.stack_port, "sync": "marks"}
    # A stack may drive as fast as the traffic it follows ever goes; never slower than it starts.
    cruise_mps = max(vehicle.speed_mps, fastest_traffic_mps(config), MIN_CRUISE_SPEED_MPS)
    planner = {"station_id": vehicle.station_id, "scenario": f"SCENARIO_{config.mission.name}",
               "platoon_id": vehicle.platoon or 0, "clock_epoch_utc": config.utc_epoch.isoformat(),
               "logic": {"cruise_speed_mps": cruise_mps, "merge": {"ego_length_m": description.length_m},
                         "signals": {"rear_axle_to_front_m": description.front_bumper_x_m},
                         "intersection": {"organiser_station_ids": [v.station_id for v in config.vehicles
                                                                    if v.organiser]}}}
    sensors = config.sensors_of(vehicle)
    geolocation = {"vehicle": vehicle.profile.value,
                   "geolocator": {"antenna_x_m": sensors.gnss.antenna_x_m, "antenna_y_m": sensors.gnss.antenna_y_m,
                                  "wheel_speed_std_mps": max(sensors.can_state.wheel_speed_sigma_mps, 1e-3),
                                  "gnss_time_jitter_s": sensors.gnss.timing.latency_jitter_s,
                                  **_receiver_errors(sensors.gnss)},
                   # The receiver's mean latency (its half-normal jitter included).
                   "gnss_receiver_latency_s": mean_latency_s(sensors.gnss.timing),
                   "can_latency_s": sensors.can_state.timing.latency_s,
                   "imu_latency_s": sensors.imu.timing.latency_s}
    scene = {"radar_latency_s": sensors.radar.timing.latency_s}
    truck = vehicle.profile is VehicleKind.TRUCK
    control = {"vehicle": vehicle.profile.value}
    plant = vehicle.plant_profile()
    # The simulated brake pressure follows the actuator's lag: automation braking takes this long to fade
    # below the override threshold, and must not read as the driver's foot on the brake.
    release_s = BRAKE_RELEASE_TIME_CONSTANTS * plant.response_time_constant_s + plant.response_dead_time_s
    # Likewise the wheels reach a steering command this long after it, and until then lag it, not the driver.
    steering_s = STEERING_RESPONSE_TIME_CONSTANTS * plant.steer_time_constant_s + plant.steer_dead_time_s
    actuation = {"actuator": {"pedal": (TRUCK_PEDAL_PROFILE if truck else CAR_PEDAL_PROFILE).model_dump(mode="json"),
                              "override": {"brake_release_grace_s": release_s, "steering_response_s": steering_s}}}
    return {"v2x": v2x, "planner": planner, "geolocation": geolocation, "scene": scene, "control": control,
            "actuation": actuation}
