"""The simulated radio boxes carry real GN datagrams over UDP between v2x links, through the radio channel."""

import numpy as np
import pytest

from coopdrive.launch.ports import free_udp_ports
from coopdrive.services.sim.channel_config import RadioChannelConfig
from coopdrive.services.sim.radio_box import RadioBox, RadioPorts
from coopdrive.services.sim.radio_channel import RadioChannel
from coopdrive.services.v2x.link import UdpLink

STEP_S = 0.02


@pytest.fixture
def two_vehicles():
    # Drawn together: ports drawn one by one may repeat.
    numbers = iter(free_udp_ports(4))
    ports = {vehicle: RadioPorts(next(numbers), next(numbers)) for vehicle in ("a", "b")}
    links = {vehicle: UdpLink(("127.0.0.1", p.stack_port), ("127.0.0.1", p.box_port), lambda _: None)
             for vehicle, p in ports.items()}
    boxes = []

    def make_box(**channel):
        box = RadioBox(ports, RadioChannel(RadioChannelConfig(**channel), np.random.default_rng(1)),
                       receive_timeout_s=1.0)
        boxes.append(box)
        return box

    yield make_box, links
    for link in links.values():
        link.close()
    for box in boxes:
        box.close()


POSITIONS = {"a": (0.0, 0.0), "b": (30.0, 0.0), "rsu": (100.0, 5.0)}


def test_a_vehicles_datagram_reaches_the_other_vehicle_after_the_channel_latency(two_vehicles):
    make_box, links = two_vehicles
    box = make_box(base_latency_s=0.002, jitter_s=0.0)
    links["a"].send(b"\x11gn-packet")
    box.on_transmitted("a", b"\x11gn-packet")
    assert box.step(0.0, POSITIONS) == {}  # still in the air
    marks = box.step(STEP_S, POSITIONS)
    assert marks == {"b": 1}
    assert links["b"].receive_until(marks["b"], timeout_s=1.0) == [b"\x11gn-packet"]


def test_a_roadside_unit_broadcast_reaches_every_stack_vehicle(two_vehicles):
    make_box, links = two_vehicles
    box = make_box(base_latency_s=0.0, jitter_s=0.0)
    box.broadcast("rsu", b"denm")
    assert box.step(0.0, POSITIONS) == {"a": 1, "b": 1}
    assert links["a"].receive_until(1, 1.0) == [b"denm"] and links["b"].receive_until(1, 1.0) == [b"denm"]


def test_a_lost_packet_gives_no_mark(two_vehicles):
    make_box, links = two_vehicles
    box = make_box(half_loss_distance_m=1.0, distance_scale_m=0.01, base_latency_s=0.0)
    links["a"].send(b"far")
    box.on_transmitted("a", b"far")
    assert box.step(0.0, POSITIONS) == {}
    assert box.channel.link_stats("a", "b").lost == 1


def test_a_transmission_whose_datagram_never_came_is_counted_missing(two_vehicles):
    make_box, _ = two_vehicles
    box = make_box()
    box.on_transmitted("a", b"never sent")
    assert box.stats.missing == 1


def test_a_receiver_that_waits_for_more_than_was_sent_counts_the_gap(two_vehicles):
    _, links = two_vehicles
    assert links["b"].receive_until(2, timeout_s=0.2) == []
    assert links["b"].missing_datagrams == 2
