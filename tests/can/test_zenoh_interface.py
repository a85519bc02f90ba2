"""python-can interface "coopdrive": python-can's API and tools on a simulated car's CAN bus, over real Zenoh
sessions (and a real `python -m can.player` process)."""

import subprocess
import sys
import threading
import time

import can
import pytest

from coopdrive.can import frames
from coopdrive.can.bus_reader import VehicleBusReader
from coopdrive.can.candump import CandumpLogger
from coopdrive.can.codec import VehicleCanCodec
from coopdrive.can.wire import to_protobuf
from coopdrive.launch.ports import free_tcp_port, loopback_endpoint
from coopdrive.v1 import vehicle_pb2

pytestmark = pytest.mark.whole_run

WAIT_S = 10.0
CYCLES = 200


def speed_mps(cycle: int) -> float:
    return 10.0 + 0.05 * cycle


def feedback_batch(speed_mps: float) -> vehicle_pb2.CanFrames:
    state = vehicle_pb2.VehicleCanState(wheel_speed_rear_left_mps=speed_mps, wheel_speed_rear_right_mps=speed_mps)
    return vehicle_pb2.CanFrames(frames=[to_protobuf(m) for m in VehicleCanCodec().encode_vehicle_state(state)])


def receive_while_publishing(python_can_bus: can.BusABC, publish) -> can.Message:
    """Zenoh needs a moment to propagate a new subscription: publish until the first frame arrives."""
    deadline = time.monotonic() + WAIT_S
    while time.monotonic() < deadline:
        publish()
        message = python_can_bus.recv(timeout=0.1)
        if message is not None:
            return message
    raise AssertionError("no frame arrived")


def test_python_can_opens_the_interface_by_name_and_receives_the_frames_the_simulator_put_on_the_car_s_bus(hub):
    bus, endpoint = hub
    with can.Bus(interface="coopdrive", channel="ego", connect=endpoint) as ego_can:
        first = receive_while_publishing(ego_can, lambda: bus.publish("ego", "can/vehicle", feedback_batch(14.0)))
        reader_states = []
        reader = VehicleBusReader(on_vehicle_state=reader_states.append)
        reader.feed(first)
        while not reader_states:
            reader.feed(ego_can.recv(timeout=WAIT_S))
    assert reader_states[0].wheel_speed_rear_left_mps == pytest.approx(14.0, abs=0.01)
    assert dict(reader.counters).keys() <= {"can_frames_received", "can_rejected_bad_counter"}


def test_it_hears_only_its_own_vehicle(hub):
    bus, endpoint = hub
    with can.Bus(interface="coopdrive", channel="ego", connect=endpoint) as ego_can:
        receive_while_publishing(ego_can, lambda: bus.publish("ego", "can/vehicle", feedback_batch(1.0)))
        while ego_can.recv(timeout=0.3) is not None:
            pass
        bus.publish("leader", "can/vehicle", feedback_batch(2.0))
        assert ego_can.recv(timeout=0.5) is None


def test_a_candump_log_played_by_python_can_s_player_reaches_a_service_reading_can_vehicle(hub, tmp_path):
    bus, endpoint = hub
    log = tmp_path / "drive.log"
    codec = VehicleCanCodec()
    with CandumpLogger(str(log), channel="can0") as logger:
        for k in range(CYCLES):
            for frame in codec.encode_vehicle_state(vehicle_pb2.VehicleCanState(
                    wheel_speed_rear_left_mps=speed_mps(k), wheel_speed_rear_right_mps=10.0), timestamp_s=k * 0.01):
                logger.write(frame)
    states, arrived = [], threading.Event()
    reader = VehicleBusReader(on_vehicle_state=states.append)

    def on_frames(envelope) -> None:
        reader.feed_all(envelope.message)
        if states and states[-1].wheel_speed_rear_left_mps == pytest.approx(speed_mps(CYCLES - 1), abs=0.01):
            arrived.set()

    bus.subscribe("ego", "can/vehicle", on_frames)
    # Played at the log's own pace (2 s): the first frames may go out before the sessions have met.
    completed = subprocess.run([sys.executable, "-m", "can.player", "-i", "coopdrive", "-c", "ego",
                                f"--bus-kwargs=connect={endpoint}", str(log)],
                               capture_output=True, text=True, timeout=120)
    assert completed.returncode == 0, completed.stderr
    assert arrived.wait(WAIT_S), f"{len(states)} states, counters {dict(reader.counters)}"
    assert len(states) > CYCLES / 2


def test_python_can_joins_a_realtime_run_through_its_listen_endpoint_and_hears_the_ego_s_feedback_and_radar():
    endpoint = loopback_endpoint(free_tcp_port())
    run = subprocess.Popen([sys.executable, "-m", "coopdrive.cli", "run", "follow", "--realtime", "--duration", "6",
                            "--listen", endpoint], stdout=subprocess.DEVNULL, stderr=subprocess.PIPE, text=True)
    names: set[str] = set()
    expected = {"VEH_WheelSpeeds", "VEH_Dynamics", "RDR_Object", "ACT_LongitudinalCommand"}
    try:
        with can.Bus(interface="coopdrive", channel="ego", connect=endpoint) as ego_can:
            deadline = time.monotonic() + 60.0
            while time.monotonic() < deadline and not expected <= names:
                message = ego_can.recv(timeout=0.5)
                if message is not None and not message.is_error_frame:
                    names.add(frames.load_database().get_message_by_frame_id(message.arbitration_id).name)
    finally:
        run.wait(timeout=120)
    assert expected <= names


def test_a_bad_channel_is_refused_naming_what_the_channel_is():
    with pytest.raises(can.CanInterfaceNotImplementedError, match="the channel is a vehicle id"):
        can.Bus(interface="coopdrive", channel="")
