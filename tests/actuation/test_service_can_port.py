"""The actuation service on a python-can bus (virtual here, socketcan on the vehicle): its ACT_ frames go out
on the bus each cycle and the car's VEH_ feedback frames are the vehicle state it checks the driver against."""

import logging
import queue
import uuid

import can
import pytest

from coopdrive.can.codec import VehicleCanCodec
from coopdrive.services.actuation.service import ActuationService
from coopdrive.v1 import actuation_pb2, vehicle_pb2

WAIT_S = 2.0


class BusFreeContext:
    """Just what the actuation service asks of its context, with call_soon functions run by pump()."""

    vehicle_id = "ego"
    log = logging.getLogger("test.actuation")

    def __init__(self) -> None:
        self.time_s = 0.0
        self.published: list[tuple[str, object]] = []
        self.calls: queue.Queue = queue.Queue()

    def now_s(self) -> float:
        return self.time_s

    def subscribe(self, topic, handler, vehicle_id=None) -> None:
        pass

    def publish(self, topic, message, sample_time_s=None) -> None:
        self.published.append((topic, message))

    def every(self, period_s, handler) -> None:
        pass

    def watch_liveliness(self, handler) -> None:
        pass

    def call_soon(self, function) -> None:
        self.calls.put(function)

    def pump(self) -> None:
        self.calls.get(timeout=WAIT_S)()


@pytest.fixture
def service_on_bus():
    channel = f"actuation-{uuid.uuid4().hex[:8]}"
    ctx = BusFreeContext()
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
    for frame in VehicleCanCodec().encode_vehicle_state(vehicle_pb2.VehicleCanState(
            wheel_speed_rear_left_mps=5.0, wheel_speed_rear_right_mps=5.0)):
        car_end.send(frame)
    ctx.pump()
    ctx.time_s = 0.04
    service.actuate(0.04)
    assert "vehicle state received" not in unmet_for_cooperative(service)
