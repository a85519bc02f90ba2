"""A python-can interface over coopdrive's Zenoh bus, so python-can's tools reach a simulated car's CAN bus.

Registered as python-can interface "coopdrive" (entry point group `can.interface`); the channel is a vehicle id:

    can.Bus(interface="coopdrive", channel="ego", connect="tcp/127.0.0.1:7447")
    python -m can.logger -i coopdrive -c ego --bus-kwargs=connect=tcp/127.0.0.1:7447 -f drive.log

recv() yields that vehicle's frames as the simulator and its actuation service publish them (can/vehicle
batches, can/command frames); send() puts a frame on its can/vehicle topic, as an ECU on the car's bus would,
e.g. `python -m can.player` replaying a candump log from the road into a service running at a desk on the wall
clock. Lockstep runs step only on the simulator's frames: do not send into one. On the vehicle, use socketcan.
"""

from __future__ import annotations

import queue
from typing import Any

import can
import zenoh

from coopdrive.bus import Bus, BusConfig, Envelope
from coopdrive.can.wire import COMMAND_TOPIC, VEHICLE_BUS_TOPIC, to_protobuf, to_python_can
from coopdrive.v1 import vehicle_pb2


class CoopdriveBus(can.BusABC):
    def __init__(self, channel: str, can_filters: can.typechecking.CanFilters | None = None,
                 connect: str | list[str] | None = None, receive_own_messages: bool = False,
                 **kwargs: Any) -> None:
        """channel: the vehicle id; connect: the Zenoh endpoint(s) of the run's hub or a zenohd router."""
        if not channel:
            raise can.CanInterfaceNotImplementedError("coopdrive: the channel is a vehicle id, e.g. 'ego'")
        endpoints = [connect] if isinstance(connect, str) else list(connect or [])
        try:
            self._bus = Bus(BusConfig(connect=endpoints, listen=[]))
        except zenoh.ZError as error:
            raise can.CanInitializationError(f"coopdrive: cannot connect to {endpoints}: {error}") from error
        self.channel_info = f"coopdrive vehicle {channel} over Zenoh {', '.join(endpoints) or '(no endpoint)'}"
        self._received: queue.SimpleQueue[can.Message] = queue.SimpleQueue()
        self._bus.subscribe(channel, VEHICLE_BUS_TOPIC, self._on_frames)
        self._bus.subscribe(channel, COMMAND_TOPIC, self._on_frame)
        self._receive_own_messages = receive_own_messages
        self._key = self._bus.layout.topic(channel, VEHICLE_BUS_TOPIC)
        schema = vehicle_pb2.CanFrames.DESCRIPTOR.full_name
        self._publisher = self._bus.session.declare_publisher(
            self._key, encoding=zenoh.Encoding.APPLICATION_PROTOBUF.with_schema(schema),
            allowed_destination=zenoh.Locality.REMOTE)
        super().__init__(channel=channel, can_filters=can_filters, **kwargs)

    def _on_frames(self, envelope: Envelope) -> None:
        for frame in envelope.message.frames:
            self._received.put(to_python_can(frame))

    def _on_frame(self, envelope: Envelope) -> None:
        self._received.put(to_python_can(envelope.message))

    def _recv_internal(self, timeout: float | None) -> tuple[can.Message | None, bool]:
        try:
            return self._received.get(timeout=timeout), False
        except queue.Empty:
            return None, False

    def send(self, msg: can.Message, timeout: float | None = None) -> None:
        frames = vehicle_pb2.CanFrames(frames=[to_protobuf(msg)])
        if self._receive_own_messages:
            self._bus.put(self._key, frames)  # to the others and, through the bus's own delivery, to ourselves
        else:
            self._publisher.put(frames.SerializeToString())

    def shutdown(self) -> None:
        super().shutdown()
        self._publisher.undeclare()
        self._bus.close()
