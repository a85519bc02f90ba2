"""Free loopback ports: TCP for per-run Zenoh endpoints, UDP for the simulated radio boxes."""

import fcntl
import os
import random
import socket
import tempfile
import threading
import time
from pathlib import Path

EPHEMERAL_RANGE_FILE = Path("/proc/sys/net/ipv4/ip_local_port_range")
# Where the radio ports are drawn from when the kernel's ephemeral range leaves no room below it.
FALLBACK_RANGE = (10000, 32768)
LOWEST_PORT = 10000
MAX_ATTEMPTS = 10000
# A drawn port stays leased this long to the process that drew it: its run's services bind it seconds later, and
# far later on a loaded machine (a sweep beside the test suite at nice 19), while other runs and tests draw too.
LEASE_S = 300.0
# One folder per user: another user's folder is not ours to create lease files in.
LEASE_DIR = Path(tempfile.gettempdir()) / f"coopdrive-udp-leases-{os.getuid()}"

_leases: list[tuple[float, int]] = []  # (expiry on the monotonic clock, locked file descriptor)
_leases_lock = threading.Lock()


def free_tcp_port() -> int:
    with socket.socket(socket.AF_INET, socket.SOCK_STREAM) as probe:
        probe.bind(("127.0.0.1", 0))
        return probe.getsockname()[1]


def loopback_endpoint(port: int) -> str:
    return f"tcp/127.0.0.1:{port}"


def free_udp_ports(count: int) -> list[int]:
    """count distinct free UDP ports below the kernel's ephemeral range, each leased for LEASE_S.

    Below it, because a socket that sends before it binds gets an ephemeral port from the kernel, and one did
    take a stack's radio port between this probe and the v2x service's bind. Every probe stays bound until all
    are found, so no port is handed out twice. The lease (an flock on a file named after the port, released
    when it expires or the process ends) keeps every other draw in any coopdrive process from handing the port
    out meanwhile: a probe only finds a port nobody has bound yet, and CI's sweep once lost a run when a test
    beside it drew a stack's port before the stack had bound it ("Address already in use").
    """
    low, high = _below_ephemeral_range()
    draw = random.SystemRandom()
    probes: list[socket.socket] = []
    leases: list[int] = []
    _end_expired_leases()
    LEASE_DIR.mkdir(exist_ok=True)
    try:
        for _ in range(MAX_ATTEMPTS):
            if len(probes) == count:
                _keep_leases(leases)
                leases = []
                return [probe.getsockname()[1] for probe in probes]
            port = draw.randrange(low, high)
            lease = _take_lease(port)
            if lease is None:
                continue
            probe = socket.socket(socket.AF_INET, socket.SOCK_DGRAM)
            try:
                probe.bind(("127.0.0.1", port))
            except OSError:
                probe.close()
                os.close(lease)
                continue
            probes.append(probe)
            leases.append(lease)
        raise OSError(f"no {count} free UDP ports in {low}-{high}")
    finally:
        for probe in probes:
            probe.close()
        for lease in leases:
            os.close(lease)


def _take_lease(port: int) -> int | None:
    """A locked descriptor of the port's lease file, or None when another draw holds the port."""
    fd = os.open(LEASE_DIR / f"{port}", os.O_RDWR | os.O_CREAT, 0o666)
    try:
        fcntl.flock(fd, fcntl.LOCK_EX | fcntl.LOCK_NB)
    except OSError:
        os.close(fd)
        return None
    return fd


def _keep_leases(fds: list[int]) -> None:
    expiry = time.monotonic() + LEASE_S
    with _leases_lock:
        _leases.extend((expiry, fd) for fd in fds)


def _end_expired_leases() -> None:
    now = time.monotonic()
    with _leases_lock:
        expired = [fd for expiry, fd in _leases if expiry <= now]
        _leases[:] = [(expiry, fd) for expiry, fd in _leases if expiry > now]
    for fd in expired:
        os.close(fd)


def free_udp_port() -> int:
    return free_udp_ports(1)[0]


def _below_ephemeral_range() -> tuple[int, int]:
    try:
        ephemeral_low = int(EPHEMERAL_RANGE_FILE.read_text().split()[0])
    except (OSError, ValueError, IndexError):
        return FALLBACK_RANGE
    return (LOWEST_PORT, ephemeral_low) if ephemeral_low > LOWEST_PORT + 1000 else FALLBACK_RANGE
