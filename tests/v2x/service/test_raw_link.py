"""The raw link: GN frames on a network interface through an AF_PACKET socket (ethertype 0x8947), here on the
loopback interface, where every frame sent is also seen by every packet socket bound to it."""

import errno
import socket
import threading

import pytest

from coopdrive.runtime.service import HardwareUnavailable
from coopdrive.services.v2x.config import LinkType, V2xConfig
from coopdrive.services.v2x.raw_link import ETHERNET_HEADER_BYTES, PACKET_OUTGOING, RawLink, RawLinkError
from coopdrive.services.v2x.service import open_link

MAC_A = bytes.fromhex("020000000a01")
MAC_B = bytes.fromhex("020000000b02")
WAIT_S = 2.0
GN_PACKET = bytes.fromhex("11000501") + bytes(40)


def can_open_a_packet_socket() -> bool:
    try:
        socket.socket(socket.AF_PACKET, socket.SOCK_RAW, 0).close()
        return True
    except PermissionError:
        return False


needs_cap_net_raw = pytest.mark.skipif(not can_open_a_packet_socket(), reason="this process lacks CAP_NET_RAW")


class Heard:
    def __init__(self):
        self.packets: list[bytes] = []
        self.arrived = threading.Event()

    def __call__(self, packet: bytes) -> None:
        self.packets.append(packet)
        self.arrived.set()


@needs_cap_net_raw
def test_a_packet_sent_on_one_raw_link_reaches_another_on_the_same_interface_without_its_ethernet_header():
    heard_by_a, heard_by_b = Heard(), Heard()
    a, b = RawLink("lo", MAC_A, heard_by_a), RawLink("lo", MAC_B, heard_by_b)
    a.start(), b.start()
    try:
        assert a.send(GN_PACKET)
        assert heard_by_b.arrived.wait(WAIT_S)
        assert heard_by_b.packets == [GN_PACKET]
        assert heard_by_a.packets == []  # our own frames are not heard back
    finally:
        a.close(), b.close()


@needs_cap_net_raw
def test_the_frame_on_the_wire_is_broadcast_from_our_mac_with_the_geonetworking_ethertype():
    sniffer = socket.socket(socket.AF_PACKET, socket.SOCK_RAW, socket.htons(0x8947))
    sniffer.bind(("lo", 0x8947))
    sniffer.settimeout(WAIT_S)
    link = RawLink("lo", MAC_A, Heard())
    try:
        link.send(GN_PACKET)
        frame = sniffer.recv(2048)
        assert frame[:6] == b"\xff" * 6 and frame[6:12] == MAC_A and frame[12:14] == b"\x89\x47"
        assert frame[ETHERNET_HEADER_BYTES:] == GN_PACKET
    finally:
        sniffer.close(), link.close()


@needs_cap_net_raw
def test_a_missing_interface_is_one_line_naming_it_and_is_hardware_unavailable():
    with pytest.raises(RawLinkError, match="no network interface 'ocb9'") as raised:
        RawLink("ocb9", MAC_A, Heard())
    assert isinstance(raised.value, HardwareUnavailable)
    assert "\n" not in str(raised.value)


def test_without_cap_net_raw_the_error_says_what_the_process_lacks(monkeypatch):
    def refused(*_args):
        raise PermissionError(errno.EPERM, "Operation not permitted")

    monkeypatch.setattr(socket, "socket", refused)
    with pytest.raises(RawLinkError, match="needs CAP_NET_RAW"):
        RawLink("wlan0", MAC_A, Heard())


def test_frames_of_our_own_and_runts_are_not_handed_on():
    link = RawLink.__new__(RawLink)
    heard = Heard()
    link._source_mac, link._on_packet, link.runt_frames = MAC_A, heard, 0
    header_from_b = b"\xff" * 6 + MAC_B + b"\x89\x47"
    link.on_frame(header_from_b + GN_PACKET, PACKET_OUTGOING)
    link.on_frame(b"\xff" * 6 + MAC_A + b"\x89\x47" + GN_PACKET, 0)
    link.on_frame(header_from_b, 0)
    link.on_frame(header_from_b + GN_PACKET, 0)
    assert heard.packets == [GN_PACKET] and link.runt_frames == 1


def test_a_raw_link_config_names_its_interface_and_is_opened_as_one():
    config = V2xConfig.model_validate({"link": {"type": "raw", "interface": "ocb0"}})
    assert config.link.type is LinkType.RAW
    with pytest.raises(ValueError, match="type raw needs the network interface"):
        V2xConfig.model_validate({"link": {"type": "raw"}})
    with pytest.raises(RawLinkError):
        open_link(V2xConfig.model_validate({"link": {"type": "raw", "interface": "no-such-if0"}}), Heard())


@needs_cap_net_raw
def test_the_service_on_a_missing_interface_exits_with_one_line_naming_it(spawn, endpoint, tmp_path):
    config = tmp_path / "v2x.yaml"
    config.write_text("link: {type: raw, interface: ocb9}\n")
    process = spawn("service", "v2x", "--config", str(config), "--vehicle", "ego", "--connect", endpoint)
    _, stderr = process.communicate(timeout=60)
    assert process.returncode != 0
    assert stderr.strip() == "coopdrive: v2x raw link: no network interface 'ocb9' (see `ip link`)"
