import math

import numpy as np
import pytest

from coopdrive.services.sim.channel_config import GilbertElliottConfig, RadioChannelConfig
from coopdrive.services.sim.radio_channel import RadioChannel, RadioNode
from coopdrive.services.sim.world_profile import ideal

PACKETS = 10000


def _channel(seed=11, **config):
    return RadioChannel(ideal(RadioChannelConfig(**config)), np.random.default_rng(seed))


def _send_many(channel, distance_m, count=PACKETS):
    sender, receiver = RadioNode("a", 0.0, 0.0), RadioNode("b", distance_m, 0.0)
    return [bool(channel.deliver(b"cam", sender, [receiver], k * 0.04)) for k in range(count)]


def test_distance_loss_is_half_at_the_half_loss_distance_and_grows_with_distance():
    channel = _channel()
    assert np.mean(_send_many(channel, 500.0)) == pytest.approx(0.5, abs=0.025)
    assert np.mean(_send_many(channel, 100.0)) > 0.999
    assert not any(_send_many(channel, 1500.0, 200))
    stats = channel.link_stats("a", "b")
    assert stats.sent == 2 * PACKETS + 200


def test_gilbert_elliott_loss_rate_and_burst_length_match_the_configuration():
    burst = ideal(GilbertElliottConfig(good_to_bad_probability=0.02, bad_to_good_probability=0.25,
                                 loss_in_good_probability=0.0, loss_in_bad_probability=0.9))
    received = np.array(_send_many(_channel(burst=burst), 10.0, 40000))
    assert 1.0 - received.mean() == pytest.approx(burst.mean_loss_probability, rel=0.08)
    # Losses come in runs: mean run of consecutive losses well above the 1 / (1 - p) of independent losses.
    lost = ~received
    edges = np.flatnonzero(np.diff(np.concatenate(([0], lost.astype(int), [0]))))
    runs = edges[1::2] - edges[::2]
    independent_run = 1.0 / (1.0 - burst.mean_loss_probability)
    assert runs.mean() > 2.5 * independent_run
    assert runs.mean() == pytest.approx(1.0 / (1.0 - 0.9 * 0.75), rel=0.1)


def test_latency_and_jitter_match_the_configuration_and_deliveries_come_in_arrival_order():
    channel = _channel(base_latency_s=0.005, jitter_s=0.002)
    sender = RadioNode("a", 0.0, 0.0)
    receivers = [RadioNode(f"r{k}", 10.0 * k, 0.0) for k in range(1, 9)]
    delays = []
    for k in range(1500):
        deliveries = channel.deliver(b"x", sender, receivers, k * 0.001)
        arrivals = [d.arrival_time_s for d in deliveries]
        assert arrivals == sorted(arrivals)
        delays.extend(d.arrival_time_s - d.send_time_s for d in deliveries)
    assert np.mean(delays) == pytest.approx(0.005 + 0.002 * math.sqrt(2.0 / math.pi), rel=0.02)
    assert min(delays) >= 0.005
    due = channel.due(10.0)
    assert [d.arrival_time_s for d in due] == sorted(d.arrival_time_s for d in due)
    assert len(due) == len(delays) and channel.in_flight == 0


def test_nothing_is_due_before_its_arrival_time():
    channel = _channel(base_latency_s=0.01, jitter_s=0.0)
    channel.deliver(b"x", RadioNode("a", 0, 0), [RadioNode("b", 5, 0)], 1.0)
    assert channel.due(1.005) == []
    assert [d.packet for d in channel.due(1.01)] == [b"x"]


def test_the_same_seed_gives_the_same_deliveries():
    burst = ideal(GilbertElliottConfig(good_to_bad_probability=0.1, bad_to_good_probability=0.3))
    a = _send_many(_channel(seed=3, burst=burst), 450.0, 2000)
    b = _send_many(_channel(seed=3, burst=burst), 450.0, 2000)
    assert a == b


def test_fault_hooks_drop_a_nodes_packets_and_corrupt_payloads():
    channel = _channel()
    channel.set_loss(1.0, node_id="b")
    assert not any(_send_many(channel, 10.0, 100))
    channel.set_loss(0.0, node_id="b")
    channel.set_corruption(1.0)
    delivery = channel.deliver(b"abcdef", RadioNode("a", 0, 0), [RadioNode("b", 5, 0)], 0.0)[0]
    assert delivery.corrupted and delivery.packet != b"abcdef" and len(delivery.packet) == 6
