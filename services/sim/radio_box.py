"""RadioBox: the simulated radio boxes of the stack vehicles, joined by the radio channel.

Each stack's v2x service talks to "its" box over UDP exactly as on the vehicle (raw GN packets, one per
datagram). Here one object plays every box: a socket per vehicle takes that vehicle's transmissions, the
RadioChannel decides who hears them when, and the survivors go out as datagrams to the receivers' v2x
ports. Scripted participants broadcast straight into the channel.

Lockstep: a box reads a vehicle's datagram when the vehicle's `v2x/tx` message for it is handled (the v2x
service sends the datagram first, so it is already waiting), and the simulator publishes each receiver's
running datagram count on `radio/mark`, which that v2x service reads up to before its step.
"""

from __future__ import annotations

import socket
from dataclasses import dataclass, field
from typing import Callable, Mapping

from coopdrive.services.sim.radio_channel import RadioChannel, RadioNode

LOOPBACK = "127.0.0.1"
MAX_DATAGRAM_BYTES = 2048


@dataclass(frozen=True)
class RadioPorts:
    # Where the box listens for the vehicle's transmissions (the v2x service's radio_port).
    box_port: int
    # Where the vehicle's v2x service listens (its listen_port).
    stack_port: int


@dataclass
class RadioBoxStats:
    # Transmissions whose datagram did not arrive in time, or differed from the bus copy.
    missing: int = 0
    mismatched: int = 0
    sent_to: dict[str, int] = field(default_factory=dict)


class RadioBox:
    def __init__(self, links: Mapping[str, RadioPorts], channel: RadioChannel, receive_timeout_s: float = 2.0,
                 host: str = LOOPBACK):
        self.channel = channel
        self.stats = RadioBoxStats(sent_to={vehicle_id: 0 for vehicle_id in links})
        self._host = host
        self._timeout_s = receive_timeout_s
        self._stack_ports = {vehicle_id: ports.stack_port for vehicle_id, ports in links.items()}
        self._sockets: dict[str, socket.socket] = {}
        for vehicle_id, ports in links.items():
            sock = socket.socket(socket.AF_INET, socket.SOCK_DGRAM)
            sock.bind((host, ports.box_port))
            sock.settimeout(receive_timeout_s)
            self._sockets[vehicle_id] = sock
        self._pending: list[tuple[str, bytes]] = []

    def on_transmitted(self, vehicle_id: str, bus_copy: bytes) -> None:
        """The vehicle's v2x service reported sending `bus_copy`: take its datagram off the box's socket."""
        try:
            datagram = self._sockets[vehicle_id].recv(MAX_DATAGRAM_BYTES)
        except (socket.timeout, OSError):
            self.stats.missing += 1
            return
        if datagram != bus_copy:
            self.stats.mismatched += 1
        self._pending.append((vehicle_id, datagram))

    def broadcast(self, sender_id: str, packet: bytes) -> None:
        """A scripted participant or roadside unit transmits (it has no stack, so no socket)."""
        self._pending.append((sender_id, packet))

    def step(self, now_s: float, positions_m: Mapping[str, tuple[float, float]],
             on_air: Callable[[str, bytes], bool] | None = None) -> dict[str, int]:
        """Puts this step's transmissions on the air and sends what arrives by now_s.

        Returns the stack vehicles that were sent something, with their running datagram count (radio/mark).
        Senders without a known position are not on the air, nor transmissions on_air(sender, packet) refuses.
        """
        nodes = [RadioNode(node_id, x_m, y_m) for node_id, (x_m, y_m) in positions_m.items()]
        receivers = [node for node in nodes if node.node_id in self._sockets]
        by_id = {node.node_id: node for node in nodes}
        pending, self._pending = self._pending, []
        for sender_id, packet in pending:
            if sender_id in by_id and (on_air is None or on_air(sender_id, packet)):
                self.channel.deliver(packet, by_id[sender_id], receivers, now_s)
        marks: dict[str, int] = {}
        for delivery in self.channel.due(now_s):
            receiver = delivery.receiver_id
            try:
                self._sockets[receiver].sendto(delivery.packet, (self._host, self._stack_ports[receiver]))
            except OSError:
                continue  # the receiver's service is gone; its mark must not count this one
            self.stats.sent_to[receiver] += 1
            marks[receiver] = self.stats.sent_to[receiver]
        return marks

    def close(self) -> None:
        for sock in self._sockets.values():
            sock.close()
        self._sockets.clear()
