"""The Service base class and the context through which a service reaches the bus.

A service is configured (constructed with its validated config and a context), started
(declares its data triggers with `ctx.subscribe` and time triggers with `ctx.every`) and
stopped. The context is a live bus in `coopdrive service`, and a recording in `coopdrive
replay`: the service cannot tell the difference, which is what makes replay exact.
"""

from __future__ import annotations

import logging
from typing import Callable, ClassVar, Protocol

from google.protobuf.message import Message
from pydantic import BaseModel, ConfigDict, Field

from coopdrive.bus import Envelope


class HardwareUnavailable(RuntimeError):
    """A device a service's config names (serial port, CAN interface) cannot be opened: its message is one line
    naming the device and why, which is all `coopdrive service` prints."""


class ServiceContext(Protocol):
    vehicle_id: str
    log: logging.Logger
    # False under replay: a service's hardware inputs (serial ports, CAN interfaces, the radio box) then come
    # from the topics its driver side published when the drive was recorded (gnss/nmea, can/vehicle, v2x/rx).
    opens_hardware: bool
    # How the service's bus session reaches the others: "mtls", "plain-loopback" or "plain" (bus/bus_mode.py).
    bus_mode: str

    def now_s(self) -> float: ...

    def subscribe(self, topic: str, handler: Callable[[Envelope], None], vehicle_id: str | None = None) -> None: ...

    def publish(self, topic: str, message: Message, sample_time_s: float | None = None) -> None: ...

    def every(self, period_s: float, handler: Callable[[float], None]) -> None: ...

    def call_soon(self, function: Callable[[], None]) -> None:
        """Runs function on the service's worker thread; for inputs from sockets, serial ports, CAN.

        Thread-safe. In lockstep the call runs before the next step the service handles.
        """

    def watch_liveliness(self, handler: Callable[[str, bool], None]) -> None:
        """handler("<vehicle>/<service>", alive) for every service present now and every change."""

    def request_stop(self, reason: str) -> None: ...


class SequenceCounter:
    """Numbers each service's messages per "<vehicle>/<topic>" and fills their Header."""

    def __init__(self, sender: str):
        self.sender = sender
        self.last: dict[str, int] = {}

    def stamp(self, message: Message, vehicle_id: str, topic: str, now_s: float, sample_time_s: float | None) -> None:
        key = f"{vehicle_id}/{topic}"
        self.last[key] = self.last.get(key, 0) + 1
        header = message.header
        header.sent_time_s = now_s
        header.sample_time_s = now_s if sample_time_s is None else sample_time_s
        header.vehicle_id = vehicle_id
        header.sender = self.sender
        header.sequence = self.last[key]


class ServiceConfig(BaseModel):
    """Base of every service's config: unknown keys are errors, not silently ignored."""

    model_config = ConfigDict(extra="forbid")

    # Added to the process's nice value when the service runs as its own process: a service that serves
    # people rather than the control loop (the gateway) yields the CPU to it on a busy machine.
    cpu_nice: int = Field(0, ge=0, le=19)


class Service:
    name: ClassVar[str]
    Config: ClassVar[type[ServiceConfig]] = ServiceConfig

    def __init__(self, config: ServiceConfig, ctx: ServiceContext):
        self.config = config
        self.ctx = ctx
        self.counters: dict[str, float] = {}

    def start(self) -> None:
        """Declare data triggers (ctx.subscribe) and time triggers (ctx.every)."""

    def stop(self) -> None:
        """Release what start() acquired (files, sockets). The runtime closes the bus."""

    def count(self, counter: str, increment: float = 1) -> None:
        self.counters[counter] = self.counters.get(counter, 0) + increment
