"""Radio ports for a run: distinct, free, out of the kernel's reach for unbound senders, and leased until bound."""

import socket
import subprocess
import sys

import pytest

from coopdrive.launch import ports as ports_module
from coopdrive.launch.ports import EPHEMERAL_RANGE_FILE, free_udp_ports


def test_a_run_gets_as_many_distinct_udp_ports_as_it_asks_for():
    ports = free_udp_ports(16)
    assert len(ports) == 16
    assert len(set(ports)) == 16


def test_every_radio_port_can_be_bound_once_handed_out():
    sockets = []
    try:
        for port in free_udp_ports(4):
            probe = socket.socket(socket.AF_INET, socket.SOCK_DGRAM)
            sockets.append(probe)
            probe.bind(("127.0.0.1", port))
    finally:
        for probe in sockets:
            probe.close()


def test_radio_ports_lie_below_the_ephemeral_range_an_unbound_sender_draws_from():
    ephemeral_low = int(EPHEMERAL_RANGE_FILE.read_text().split()[0])
    assert all(port < ephemeral_low for port in free_udp_ports(16))


def confine_draws_to_one_free_port(monkeypatch) -> int:
    """A port free now, unleased, and the only one draws may take (each tries it 50 times)."""
    monkeypatch.setattr(ports_module, "LEASE_S", 0.0)
    (port,) = free_udp_ports(1)
    monkeypatch.setattr(ports_module, "_below_ephemeral_range", lambda: (port, port + 1))
    monkeypatch.setattr(ports_module, "MAX_ATTEMPTS", 50)
    return port


def test_a_drawn_port_is_not_handed_out_again_while_its_lease_lasts_in_this_process_or_another(monkeypatch):
    port = confine_draws_to_one_free_port(monkeypatch)
    monkeypatch.setattr(ports_module, "LEASE_S", 300.0)
    assert free_udp_ports(1) == [port]
    with pytest.raises(OSError, match=f"no 1 free UDP ports in {port}-{port + 1}"):
        free_udp_ports(1)
    other_process = subprocess.run(
        [sys.executable, "-c", "from coopdrive.launch import ports\n"
                               f"ports._below_ephemeral_range = lambda: ({port}, {port + 1})\n"
                               "ports.MAX_ATTEMPTS = 50\n"
                               "print(ports.free_udp_ports(1))"], capture_output=True, text=True, timeout=60)
    assert other_process.returncode != 0 and "no 1 free UDP ports" in other_process.stderr


def test_a_port_whose_lease_ended_can_be_drawn_again(monkeypatch):
    port = confine_draws_to_one_free_port(monkeypatch)
    assert free_udp_ports(1) == [port]
    assert free_udp_ports(1) == [port]
