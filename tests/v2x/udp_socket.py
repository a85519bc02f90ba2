"""A UDP socket on a free loopback port: the radio box's end of a v2x service's link, or a listener, in the tests."""

import socket


def loopback_udp_socket(timeout_s: float | None = None) -> socket.socket:
    """timeout_s: None blocks, 0.0 never waits (see socket.settimeout)."""
    sock = socket.socket(socket.AF_INET, socket.SOCK_DGRAM)
    sock.bind(("127.0.0.1", 0))
    sock.settimeout(timeout_s)
    return sock
