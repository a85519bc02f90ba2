"""Free loopback ports: TCP for per-run Zenoh endpoints, UDP for the simulated radio boxes."""

import random
import socket
from pathlib import Path

EPHEMERAL_RANGE_FILE = Path("/proc/sys/net/ipv4/ip_local_port_range")
# Where the radio ports are drawn from when the kernel's ephemeral range leaves no room below it.
FALLBACK_RANGE = (10000, 32768)
LOWEST_PORT = 10000
MAX_ATTEMPTS = 10000


def free_tcp_port() -> int:
    with socket.socket(socket.AF_INET, socket.SOCK_STREAM) as probe:
        probe.bind(("127.0.0.1", 0))
        return probe.getsockname()[1]


def loopback_endpoint(port: int) -> str:
    return f"tcp/127.0.0.1:{port}"


def free_udp_ports(count: int) -> list[int]:
    """count distinct free UDP ports below the kernel's ephemeral range.

    Below it, because a socket that sends before it binds gets an ephemeral port from the kernel, and one did
    take a stack's radio port between this probe and the v2x service's bind. Every probe stays bound until all
    are found, so no port is handed out twice.
    """
    low, high = _below_ephemeral_range()
    draw = random.SystemRandom()
    probes: list[socket.socket] = []
    try:
        for _ in range(MAX_ATTEMPTS):
            if len(probes) == count:
                return [probe.getsockname()[1] for probe in probes]
            probe = socket.socket(socket.AF_INET, socket.SOCK_DGRAM)
            try:
                probe.bind(("127.0.0.1", draw.randrange(low, high)))
            except OSError:
                probe.close()
                continue
            probes.append(probe)
        raise OSError(f"no {count} free UDP ports in {low}-{high}")
    finally:
        for probe in probes:
            probe.close()


def free_udp_port() -> int:
    return free_udp_ports(1)[0]


def _below_ephemeral_range() -> tuple[int, int]:
    try:
        ephemeral_low = int(EPHEMERAL_RANGE_FILE.read_text().split()[0])
    except (OSError, ValueError, IndexError):
        return FALLBACK_RANGE
    return (LOWEST_PORT, ephemeral_low) if ephemeral_low > LOWEST_PORT + 1000 else FALLBACK_RANGE
