"""Radio ports for a run: distinct, free, and out of the kernel's reach for unbound senders."""

import socket

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
