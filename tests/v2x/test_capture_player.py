"""`coopdrive v2x replay`: a real capture's GN packets reach a loopback radio-box port as the box sends them."""

import socket
import subprocess
import sys
import time
from concurrent.futures import ThreadPoolExecutor

import dpkt
import pytest

from coopdrive.v2x.geonet import parse_basic_header
from coopdrive.services.v2x.capture_player import ReplayError, UdpSink, replay_capture
from coopdrive.services.v2x.raw_link import MAX_FRAME_BYTES, PACKET_OUTGOING, open_packet_socket
from coopdrive.recording.capture import read_gn_packets
from tests.shared_data import shared_file
from tests.v2x.service.test_raw_link import needs_cap_net_raw
from tests.v2x.udp_socket import loopback_udp_socket

SIGNED = "v2x/considerit_signed_testvectors.pcap"
# Two stations (a vehicle and a pedestrian), each from its own MAC: beacons, CAMs and VAMs.
FLEXSTACK = "v2x/flexstack_cam_vam_beacons.pcap"
# The capture's four frames are stamped one second apart.
RECORDED_GAP_S = 1.0
RATE = 10.0
# A bound on waiting for a frame already sent: a lost frame fails the test instead of hanging it.
WAIT_FOR_FRAME_S = 10.0
SECURED_NEXT_HEADER = 2


@pytest.fixture
def radio_port():
    sock = loopback_udp_socket(5.0)
    yield sock
    sock.close()


def received(sock: socket.socket, count: int) -> list[tuple[float, bytes]]:
    """(arrival time, datagram) of the next count datagrams."""
    arrivals = []
    for _ in range(count):
        data = sock.recv(4096)
        arrivals.append((time.monotonic(), data))
    return arrivals


def ethernet_payloads(path) -> list[bytes]:
    with open(path, "rb") as stream:
        return [bytes(dpkt.ethernet.Ethernet(frame).data) for _, frame in dpkt.pcap.Reader(stream)]


def test_the_signed_capture_arrives_as_bare_gn_datagrams_byte_for_byte_at_the_recorded_pace_scaled(radio_port):
    with ThreadPoolExecutor(1) as pool:
        replaying = pool.submit(replay_capture, shared_file(SIGNED), UdpSink(radio_port.getsockname()), RATE)
        arrivals = received(radio_port, 4)
        summary = replaying.result()
    assert summary.sent == 4 and not summary.skipped
    assert [data for _, data in arrivals] == ethernet_payloads(shared_file(SIGNED))
    # GN from the first byte: a version 1 basic header; the beacon unsecured, the three others secured
    assert [parse_basic_header(data).version for _, data in arrivals] == [1] * 4
    assert [data[0] & 0x0F for _, data in arrivals] == [1] + [SECURED_NEXT_HEADER] * 3
    # it waited for the recorded pace (how late a loaded machine lets it be is not the replay's to promise)
    assert summary.duration_s >= 3 * RECORDED_GAP_S / RATE


class FakeClock:
    """monotonic() and sleep() of a clock that only moves when slept; it keeps the times slept to."""

    def __init__(self) -> None:
        self.now_s = 100.0
        self.woken_at_s: list[float] = []

    def monotonic(self) -> float:
        return self.now_s

    def sleep(self, seconds: float) -> None:
        self.now_s += seconds
        self.woken_at_s.append(self.now_s)


def test_each_packet_waits_for_its_recorded_offset_divided_by_the_rate(radio_port):
    clock = FakeClock()
    summary = replay_capture(shared_file(SIGNED), UdpSink(radio_port.getsockname()), RATE, sleep=clock.sleep,
                             monotonic=clock.monotonic)
    assert summary.sent == 4 and len(received(radio_port, 4)) == 4
    # the first packet goes at once, each later one when its offset from the first, scaled, has passed
    assert clock.woken_at_s == pytest.approx([100.0 + k * RECORDED_GAP_S / RATE for k in (1, 2, 3)])
    assert summary.duration_s == pytest.approx(3 * RECORDED_GAP_S / RATE)


def test_a_pcapng_capture_of_929_packets_is_sent_whole(radio_port):
    radio_port.setsockopt(socket.SOL_SOCKET, socket.SO_RCVBUF, 1 << 20)
    summary = replay_capture(shared_file("v2x/msvan3t_cam_cpm_trace.pcapng"), UdpSink(radio_port.getsockname()),
                             rate=1e6)
    assert summary.sent == 929 and summary.send_errors == 0
    assert len(received(radio_port, 929)) == 929


def test_frames_of_another_ethertype_are_skipped_and_counted(tmp_path, radio_port):
    capture = tmp_path / "mixed.pcap"
    with open(capture, "wb") as stream:
        writer = dpkt.pcap.Writer(stream)
        gn = ethernet_payloads(shared_file(SIGNED))[0]
        writer.writepkt(bytes(dpkt.ethernet.Ethernet(src=b"\x02" * 6, dst=b"\xff" * 6, type=0x0800, data=b"ip")), 1.0)
        writer.writepkt(bytes(dpkt.ethernet.Ethernet(src=b"\x02" * 6, dst=b"\xff" * 6, type=0x8947, data=gn)), 1.0)
    summary = replay_capture(capture, UdpSink(radio_port.getsockname()))
    assert summary.sent == 1 and dict(summary.skipped) == {"other_ethertype": 1}
    assert radio_port.recv(4096) == gn


def test_a_rate_of_zero_is_refused(radio_port):
    with pytest.raises(ReplayError, match="--rate 0"):
        replay_capture(shared_file(SIGNED), UdpSink(radio_port.getsockname()), rate=0.0)


def test_the_command_reports_what_it_sent_and_refuses_a_file_that_is_no_capture_in_one_line(tmp_path, radio_port):
    port = radio_port.getsockname()[1]
    done = subprocess.run([sys.executable, "-m", "coopdrive.cli", "v2x", "replay", str(shared_file(SIGNED)),
                           "--address", "127.0.0.1", "--port", str(port), "--rate", "100"],
                          capture_output=True, text=True, timeout=60)
    assert done.returncode == 0, done.stderr
    assert done.stdout.startswith(f"sent 4 GN packets to 127.0.0.1:{port} in ")
    (tmp_path / "notes.txt").write_text("not a capture")
    bad = subprocess.run([sys.executable, "-m", "coopdrive.cli", "v2x", "replay", str(tmp_path / "notes.txt"),
                          "--port", str(port)], capture_output=True, text=True, timeout=60)
    assert bad.returncode == 2 and bad.stderr.count("\n") == 1 and "not a pcap or pcapng file" in bad.stderr


@needs_cap_net_raw
def test_the_command_sends_a_capture_onto_an_interface_as_its_stations_sent_it():
    """Each GN packet as a broadcast frame of ethertype 0x8947 from the MAC the capture shows for its sender, on the
    loopback interface here (an OCB interface on a vehicle)."""
    recorded = list(read_gn_packets(shared_file(FLEXSTACK)))
    sniffer = open_packet_socket("lo")
    sniffer.settimeout(WAIT_FOR_FRAME_S)
    try:
        done = subprocess.run([sys.executable, "-m", "coopdrive.cli", "v2x", "replay", str(shared_file(FLEXSTACK)),
                               "--interface", "lo", "--rate", "100"], capture_output=True, text=True, timeout=60)
        assert done.returncode == 0, done.stderr
        assert done.stdout.startswith(f"sent {len(recorded)} GN packets onto lo in ")
        frames = []
        while len(frames) < len(recorded):
            frame, address = sniffer.recvfrom(MAX_FRAME_BYTES)
            if address[2] != PACKET_OUTGOING:  # loopback shows each frame going out and coming in
                frames.append(frame)
    finally:
        sniffer.close()
    assert [frame[:6] for frame in frames] == [b"\xff" * 6] * len(recorded)
    assert [frame[6:12] for frame in frames] == [packet.source_mac for packet in recorded]
    assert len({packet.source_mac for packet in recorded}) == 2  # FlexStack's vehicle and its pedestrian
    assert [frame[12:14] for frame in frames] == [b"\x89\x47"] * len(recorded)
    assert [frame[14:] for frame in frames] == [packet.gn_packet for packet in recorded]


@needs_cap_net_raw
def test_the_command_onto_a_missing_interface_says_so_in_one_line():
    done = subprocess.run([sys.executable, "-m", "coopdrive.cli", "v2x", "replay", str(shared_file(SIGNED)),
                           "--interface", "ocb9"], capture_output=True, text=True, timeout=60)
    assert done.returncode == 2
    assert done.stderr == "coopdrive: v2x raw link: no network interface 'ocb9' (see `ip link`)\n"
