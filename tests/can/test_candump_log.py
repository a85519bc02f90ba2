import math

import can

from coopdrive.can.candump import CandumpLogger, read_candump
from coopdrive.can.codec import VehicleCanCodec
from coopdrive.services.actuation.actuator import Actuator
from coopdrive.v1 import actuation_pb2, control_pb2, ego_pb2, vehicle_pb2

SERVICES = ("geolocation", "scene", "planner", "control", "v2x")


def drive_actuator(steps: int) -> list[can.Message]:
    """Frames of an actuator engaged in autonomous mode following a varying command."""
    actuator = Actuator()
    for name in SERVICES:
        actuator.on_service_liveness(name, True)
    frames = []
    for i in range(steps):
        now_s = i * 0.02
        actuator.on_ego_state(ego_pb2.EgoState(mode=ego_pb2.LOCALISATION_MODE_GNSS_PRECISE), now_s)
        actuator.on_v2x_health(True, now_s)
        actuator.on_vehicle_state(vehicle_pb2.VehicleCanState(gear=vehicle_pb2.GEAR_DRIVE), now_s)
        actuator.on_control_command(control_pb2.ControlCommand(
            accel_request_mps2=1.5 * math.sin(i / 5.0), steering_angle_request_rad=0.01 * i), now_s)
        if i == 0:
            actuator.on_mode_request(actuation_pb2.ModeRequest(mode=actuation_pb2.DRIVING_MODE_AUTONOMOUS), now_s)
        frames.extend(actuator.step(now_s)[0])
    return frames


def test_frames_logged_from_the_virtual_bus_read_back_to_the_same_decoded_commands(tmp_path):
    path = tmp_path / "actuation.log"
    sent = drive_actuator(30)
    with can.Bus(interface="virtual", channel="candump-test") as sender, \
            can.Bus(interface="virtual", channel="candump-test") as monitor, CandumpLogger(path) as logger:
        for msg in sent:
            sender.send(msg)
            logger.write(monitor.recv(timeout=1.0))
    replayed = list(read_candump(path))
    assert len(replayed) == len(sent)
    live, logged = VehicleCanCodec(), VehicleCanCodec()
    expected = [live.decode_command(msg) for msg in sent]
    assert [logged.decode_command(msg) for msg in replayed] == expected
    assert any(command.throttle_ratio > 0 for command in expected)
    assert any(command.brake_ratio > 0 for command in expected)


def test_the_log_is_in_candump_format(tmp_path):
    path = tmp_path / "actuation.log"
    with CandumpLogger(path) as logger:
        logger.write_all(drive_actuator(1))
    first = path.read_text().splitlines()[0]
    timestamp, channel, frame = first.split()[:3]
    assert timestamp.startswith("(") and channel == "vcan0" and frame.startswith("100#")
