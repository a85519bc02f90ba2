"""The actuation service on a python-can bus (virtual here, socketcan on the vehicle): its ACT_ frames go out
on the bus each cycle and the car's VEH_ feedback frames are the vehicle state it checks the driver against."""

import logging
import math
import uuid

import can
import pytest
from actuation_fixtures import ALL_SERVICES, control_command, mode_request, vehicle_state

from coopdrive.can.codec import VehicleCanCodec
from coopdrive.runtime.testing import MemoryContext
from coopdrive.services.actuation.service import ActuationService
from coopdrive.v1 import actuation_pb2, ego_pb2, vehicle_pb2

WAIT_S = 2.0


@pytest.fixture
def service_on_bus():
    channel = f"actuation-{uuid.uuid4().hex[:8]}"
    ctx = MemoryContext(log=logging.getLogger("test.actuation"), opens_hardware=True, queue_calls=True)
    config = ActuationService.Config.model_validate({"can_port": {"interface": "virtual", "channel": channel}})
    service = ActuationService(config, ctx)
    service.start()
    car_end = can.Bus(interface="virtual", channel=channel)
    yield service, ctx, car_end
    car_end.shutdown()
    service.stop()


def test_each_cycle_sends_the_act_frames_on_the_vehicle_bus_as_well_as_on_can_command(service_on_bus):
    service, ctx, car_end = service_on_bus
    service.actuate(0.02)
    published = [m for topic, m in ctx.published if topic == "can/command"]
    on_the_wire = [car_end.recv(timeout=WAIT_S) for _ in published]
    assert [m.arbitration_id for m in on_the_wire] == [f.arbitration_id for f in published]
    assert service.counters["can_frames_sent"] == len(published)


def unmet_for_cooperative(service) -> str:
    return " ".join(a.unmet_condition for a in service.status.availability
                    if a.mode == actuation_pb2.DRIVING_MODE_COOPERATIVE)


def test_the_cars_feedback_frames_reach_the_actuator_as_its_vehicle_state(service_on_bus):
    service, ctx, car_end = service_on_bus
    service.actuate(0.02)
    assert "vehicle state received" in unmet_for_cooperative(service)
    feedback = VehicleCanCodec().encode_vehicle_state(vehicle_pb2.VehicleCanState(
        wheel_speed_rear_left_mps=5.0, wheel_speed_rear_right_mps=5.0))
    for frame in feedback:
        car_end.send(frame)
    ctx.pump(len(feedback))
    ctx.clock.set(0.04)
    service.actuate(0.04)
    assert "vehicle state received" not in unmet_for_cooperative(service)


def test_actuation_owns_the_car_s_bus_every_frame_it_reads_goes_on_can_vehicle_stamped_on_arrival(service_on_bus):
    service, ctx, car_end = service_on_bus
    # The car's frames carry its interface's clock; the service's clock is another.
    feedback = VehicleCanCodec().encode_vehicle_state(vehicle_pb2.VehicleCanState(), timestamp_s=46408.0)
    ctx.clock.set(1234.5)
    for frame in feedback:
        car_end.send(frame)
    ctx.pump(len(feedback))
    ctx.advance_to(ctx.now_s())
    batches = [m for topic, m in ctx.published if topic == "can/vehicle"]
    frames = [frame for batch in batches for frame in batch.frames]
    assert [f.arbitration_id for f in frames] == [f.arbitration_id for f in feedback]
    assert [f.data for f in frames] == [bytes(f.data) for f in feedback]
    assert {f.timestamp_s for f in frames} == {1234.5}
    assert service.vehicle_bus.counts()["can_frames_published"] == len(frames)


CYCLE_S = 0.01
# Slow enough to engage: the automation is switched on at walking pace.
CREEP_MPS = 1.0
DRIVER_INPUTS = {
    # The DRIVERTIVE thresholds: steering 5 deg (at the wheel) off the command for 500 ms, throttle > 10 %, any brake.
    "steering": (actuation_pb2.OVERRIDE_REASON_STEERING, {"steering_angle_rad": math.radians(10.0 / 15.0)}, 0.7),
    "throttle": (actuation_pb2.OVERRIDE_REASON_THROTTLE, {"throttle": 0.2}, 0.05),
    "brake": (actuation_pb2.OVERRIDE_REASON_BRAKE, {"brake": 0.1}, 0.05),
}


class CarOnTheBus:
    """The car's end of the bus: each cycle the world is healthy, a command is fresh, and the car sends its
    VEH_ frames carrying the driver's inputs (one codec, so the rolling counters run on)."""

    def __init__(self, service, ctx, car_end) -> None:
        self.service, self.ctx, self.car_end = service, ctx, car_end
        self.codec = VehicleCanCodec()

    def drive(self, duration_s: float, **driver) -> None:
        start_s = self.ctx.now_s()
        for k in range(1, round(duration_s / CYCLE_S) + 1):
            now_s = start_s + k * CYCLE_S
            self.ctx.clock.set(now_s)
            self.keep_the_rest_of_the_stack_healthy(now_s)
            self.service.actuator.on_control_command(control_command(0.5), now_s)
            feedback = self.codec.encode_vehicle_state(vehicle_state(CREEP_MPS, **driver))
            for frame in feedback:
                self.car_end.send(frame)
            self.ctx.pump(len(feedback))
            self.service.actuate(now_s)

    def keep_the_rest_of_the_stack_healthy(self, now_s: float) -> None:
        """What arrives over Zenoh, not CAN: the other services alive, localisation good, V2X healthy."""
        actuator = self.service.actuator
        for name in ALL_SERVICES:
            actuator.on_service_liveness(name, True)
        actuator.on_ego_state(ego_pb2.EgoState(mode=ego_pb2.LOCALISATION_MODE_GNSS_PRECISE), now_s)
        actuator.on_v2x_health(True, now_s)

    def engage_autonomous(self) -> None:
        self.drive(0.05)
        decision = self.service.actuator.on_mode_request(mode_request(actuation_pb2.DRIVING_MODE_AUTONOMOUS),
                                                         self.ctx.now_s())
        assert decision.accepted, decision.unmet
        self.drive(CYCLE_S)
        assert self.service.status.mode == actuation_pb2.DRIVING_MODE_AUTONOMOUS


@pytest.fixture
def car(service_on_bus):
    return CarOnTheBus(*service_on_bus)


@pytest.mark.parametrize("condition", list(DRIVER_INPUTS))
def test_a_driver_input_arriving_in_can_frames_hands_control_back_and_names_why(car, condition):
    reason, driver, duration_s = DRIVER_INPUTS[condition]
    car.engage_autonomous()
    car.drive(duration_s, **driver)
    assert car.service.status.mode == actuation_pb2.DRIVING_MODE_MANUAL
    events = [m for topic, m in car.ctx.published if topic == "actuation/override"]
    assert [e.reason for e in events] == [reason]
    assert car.service.counters["driver_overrides"] >= 1


def test_a_steering_touch_shorter_than_500_ms_keeps_the_automation(car):
    car.engage_autonomous()
    car.drive(0.3, steering_angle_rad=math.radians(10.0 / 15.0))
    assert car.service.status.mode == actuation_pb2.DRIVING_MODE_AUTONOMOUS
