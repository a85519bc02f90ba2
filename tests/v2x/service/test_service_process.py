"""`coopdrive service v2x` as a real process: UDP to a fake radio box on 127.0.0.1, messages on a real Zenoh bus."""

import queue
import signal
import time

from coopdrive.bus import Bus, BusConfig
from coopdrive.launch.ports import free_udp_port
from coopdrive.services.v2x.capture_decode import decode_capture
from coopdrive.v2x.packet import decode_packet
from coopdrive.v2x.timebase import ItsClock
from coopdrive.v1 import ego_pb2

from .streams import REMOTE_STATION_ID, cam_packet, remote_cam
from tests.v2x.udp_socket import loopback_udp_socket

DEADLINE_S = 30.0
STOP_TIMEOUT_S = 20.0
WALL_CLOCK = ItsClock(0.0)
OWN_STATION_ID = 1001
PERIOD_S = 0.04


def test_the_v2x_process_exchanges_packets_with_the_radio_box_and_reports_the_remote_station(endpoint, spawn,
                                                                                           tmp_path):
    hub = Bus(BusConfig(listen=[endpoint]))
    radio = loopback_udp_socket(0.0)
    listen_port = free_udp_port()
    cams: queue.Queue = queue.Queue()
    statuses: queue.Queue = queue.Queue()
    hub.subscribe("ego", "v2x/cam", cams.put)
    hub.subscribe("ego", "v2x/status", statuses.put)
    pcap = tmp_path / "v2x.pcap"
    process = spawn("service", "v2x", "--vehicle", "ego", "--connect", endpoint,
                    "--set", f"link.radio_port={radio.getsockname()[1]}", "--set", f"link.listen_port={listen_port}",
                    "--set", f"station_id={OWN_STATION_ID}", "--set", f"pcap_path={pcap}")
    ours: list[bytes] = []
    remote_seen = active_status = None
    try:
        end = time.monotonic() + DEADLINE_S
        while (remote_seen is None or active_status is None or not ours) and time.monotonic() < end:
            hub.publish("ego", "ego/state", ego_pb2.EgoState(x_m=1.0, speed_mps=10.0))
            now_s = time.time()
            radio.sendto(cam_packet(remote_cam(now_s, north_m=0.0, clock=WALL_CLOCK), now_s, clock=WALL_CLOCK),
                         ("127.0.0.1", listen_port))
            try:
                while True:
                    ours.append(radio.recv(4096))
            except BlockingIOError:
                pass
            while not cams.empty():
                remote_seen = cams.get()
            while not statuses.empty():
                status = statuses.get().message
                # ACTIVE or, on a loaded machine, LOST between two of our sends: either way it was heard.
                if status.packets_sent > 0 and any(
                        s.station_id == REMOTE_STATION_ID and s.messages_received > 0 for s in status.stations):
                    active_status = status
            time.sleep(PERIOD_S)
        assert process.poll() is None, process.stderr.read()
        assert remote_seen is not None and remote_seen.message.station_id == REMOTE_STATION_ID
        assert remote_seen.message.header.sender == "v2x"
        assert active_status is not None and active_status.packets_sent > 0, active_status
        assert decode_packet(ours[0]).station_id == OWN_STATION_ID
        process.send_signal(signal.SIGTERM)
        process.wait(timeout=STOP_TIMEOUT_S)
    finally:
        hub.close()
        radio.close()
    stations = {line.split(" station ")[1].split()[0] for line in decode_capture(pcap) if " station " in line}
    assert stations == {str(OWN_STATION_ID), str(REMOTE_STATION_ID)}
