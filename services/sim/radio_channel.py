"""The V2X radio channel: per-link distance loss, Gilbert-Elliott burst loss, latency and jitter, seeded.

Pure logic: the integrator hands packets in with the nodes' positions and takes deliveries out by time.
"""
from __future__ import annotations

import heapq
import itertools
import math
from dataclasses import dataclass, field
from typing import Sequence

import numpy as np

from coopdrive.services.sim.channel_config import RadioChannelConfig


@dataclass(frozen=True)
class RadioNode:
    node_id: str
    x_m: float
    y_m: float


@dataclass(frozen=True)
class Delivery:
    sender_id: str
    receiver_id: str
    packet: bytes
    send_time_s: float
    arrival_time_s: float
    corrupted: bool = False


@dataclass
class LinkStats:
    sent: int = 0
    lost: int = 0
    corrupted: int = 0


@dataclass
class _Link:
    bad: bool = False
    stats: LinkStats = field(default_factory=LinkStats)


class RadioChannel:
    def __init__(self, config: RadioChannelConfig, rng: np.random.Generator) -> None:
        self.config = config
        self.rng = rng
        self._links: dict[tuple[str, str], _Link] = {}
        self._queue: list[tuple[float, int, Delivery]] = []
        self._order = itertools.count()
        # Fault hooks: extra loss per node (v2v_loss; None = every node) and corruption (v2v_corruption).
        self.node_loss_probability: dict[str | None, float] = {}
        self.corruption_probability = config.corruption_probability

    def set_loss(self, probability: float, node_id: str | None = None) -> None:
        """Fault hook (v2v_loss): drop this share of packets to or from node_id (all nodes when None)."""
        if probability <= 0.0:
            self.node_loss_probability.pop(node_id, None)
        else:
            self.node_loss_probability[node_id] = min(probability, 1.0)

    def set_corruption(self, probability: float) -> None:
        """Fault hook (v2v_corruption): flip one byte of this share of delivered packets."""
        self.corruption_probability = min(max(probability, 0.0), 1.0)

    def distance_loss_probability(self, distance_m: float) -> float:
        cfg = self.config
        if distance_m > cfg.max_range_m:
            return 1.0
        z = (distance_m - cfg.half_loss_distance_m) / cfg.distance_scale_m
        return 1.0 / (1.0 + math.exp(-z)) if z > -700 else 0.0

    def link_stats(self, sender_id: str, receiver_id: str) -> LinkStats:
        return self._link(sender_id, receiver_id).stats

    def _link(self, sender_id: str, receiver_id: str) -> _Link:
        link = self._links.get((sender_id, receiver_id))
        if link is None:
            link = self._links[sender_id, receiver_id] = _Link()
        return link

    def _burst_lost(self, link: _Link) -> bool:
        ge = self.config.burst
        switch = self.rng.random()
        if link.bad:
            link.bad = switch >= ge.bad_to_good_probability
        else:
            link.bad = switch < ge.good_to_bad_probability
        loss = ge.loss_in_bad_probability if link.bad else ge.loss_in_good_probability
        return self.rng.random() < loss

    def _fault_lost(self, sender_id: str, receiver_id: str) -> bool:
        probability = max(self.node_loss_probability.get(None, 0.0),
                          self.node_loss_probability.get(sender_id, 0.0),
                          self.node_loss_probability.get(receiver_id, 0.0))
        return probability > 0.0 and self.rng.random() < probability

    def _corrupt(self, packet: bytes) -> bytes:
        if not packet:
            return packet
        data = bytearray(packet)
        index = int(self.rng.integers(len(data)))
        data[index] ^= int(self.rng.integers(1, 256))
        return bytes(data)

    def deliver(self, packet: bytes, sender: RadioNode, receivers: Sequence[RadioNode],
                now_s: float) -> list[Delivery]:
        """Schedule one broadcast; returns the deliveries that will happen, in order of arrival time.

        Every receiver draws the same number of random values whatever happens, so the outcome of one link
        does not depend on the fate of another.
        """
        scheduled = []
        for receiver in receivers:
            if receiver.node_id == sender.node_id:
                continue
            link = self._link(sender.node_id, receiver.node_id)
            link.stats.sent += 1
            distance_m = math.hypot(receiver.x_m - sender.x_m, receiver.y_m - sender.y_m)
            distance_lost = self.rng.random() < self.distance_loss_probability(distance_m)
            burst_lost = self._burst_lost(link)
            fault_lost = self._fault_lost(sender.node_id, receiver.node_id)
            delay_s = self.config.base_latency_s + abs(self.config.jitter_s * self.rng.standard_normal())
            corrupt = self.rng.random() < self.corruption_probability
            if distance_lost or burst_lost or fault_lost:
                link.stats.lost += 1
                continue
            payload = packet
            if corrupt:
                link.stats.corrupted += 1
                payload = self._corrupt(packet)
            delivery = Delivery(sender.node_id, receiver.node_id, payload, now_s, now_s + delay_s, corrupt)
            scheduled.append(delivery)
            heapq.heappush(self._queue, (delivery.arrival_time_s, next(self._order), delivery))
        scheduled.sort(key=lambda d: d.arrival_time_s)
        return scheduled

    def due(self, now_s: float) -> list[Delivery]:
        """Deliveries whose arrival time has come, in order of arrival, removed from the channel."""
        ready = []
        while self._queue and self._queue[0][0] <= now_s:
            ready.append(heapq.heappop(self._queue)[2])
        return ready

    @property
    def in_flight(self) -> int:
        return len(self._queue)
