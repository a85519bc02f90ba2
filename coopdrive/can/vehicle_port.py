"""The vehicle's own CAN bus through python-can: frames out, frames in.

On the vehicle a service opens the bus here (socketcan, a PCAN or Kvaser adapter, or any interface python-can
supports): actuation, the owner of the car's bus, sends its ACT_ frames, reads the car's feedback and publishes
every frame on can/vehicle (see bus_input.py); scene reads the radar's object lists on the radar's bus.
Received frames go to a callback (a VehicleBusReader decodes them), stamped with the service's clock on arrival:
an interface's own timestamps run on another time base. Send failures are counted, never raised; every frame in
and out can go to a candump log that can-utils' canplayer replays.
"""

from __future__ import annotations

import threading
from collections import Counter
from typing import Callable

import can
from pydantic import BaseModel, ConfigDict, Field

from coopdrive.can.candump import CandumpLogger
from coopdrive.runtime.service import HardwareUnavailable

# How long the receive thread blocks on the bus before looking whether it should stop.
RECEIVE_TIMEOUT_S = 0.1


class VehicleCanPortConfig(BaseModel):
    model_config = ConfigDict(extra="forbid")

    # A python-can interface name: socketcan on the vehicle, virtual or udp_multicast for tests and desks.
    interface: str = Field(min_length=1)
    channel: str = Field(min_length=1)
    bitrate: int | None = Field(None, gt=0)
    # Every frame in and out, in candump format ("" = no log).
    candump_path: str = ""
    # Put every frame read on the can/vehicle topic, stamped on arrival, so recordings hold the car's bus and
    # the other services read it there. None: the service's default (actuation, which owns the car's bus, does;
    # geolocation and scene with a port of their own do not). One publisher per vehicle.
    publish_frames: bool | None = None
    # How often the frames read since the last batch go out (one CanFrames batch each).
    publish_period_s: float = Field(0.01, gt=0.0)


class VehicleCanPortError(HardwareUnavailable):
    """The configured CAN interface could not be opened."""


class VehicleCanPort:
    def __init__(self, config: VehicleCanPortConfig, on_frame: Callable[[can.Message], None],
                 clock: Callable[[], float] | None = None) -> None:
        """on_frame runs on python-can's receive thread; clock (the service's now_s) restamps each frame."""
        extra = {"bitrate": config.bitrate} if config.bitrate is not None else {}
        try:
            self.bus = can.Bus(interface=config.interface, channel=config.channel, **extra)
        except (can.CanError, OSError, ValueError, ImportError, NotImplementedError) as error:
            raise VehicleCanPortError(f"can_port: {config.interface} channel {config.channel!r} could not be "
                                      f"opened: {error}") from error
        self.on_frame = on_frame
        self.clock = clock
        self.counters: Counter[str] = Counter()
        self._lock = threading.Lock()
        self._log = CandumpLogger(config.candump_path, channel=config.channel) if config.candump_path else None
        self._notifier = can.Notifier(self.bus, [self._on_message], timeout=RECEIVE_TIMEOUT_S)

    def send(self, frames: list[can.Message]) -> None:
        for frame in frames:
            try:
                self.bus.send(frame)
            except can.CanError:
                self._count("can_send_errors")
                continue
            self._count("can_frames_sent")
            self._write_log(frame)

    def _on_message(self, msg: can.Message) -> None:
        self._write_log(msg)
        if self.clock is not None:
            msg.timestamp = self.clock()
        self.on_frame(msg)

    def counts(self) -> dict[str, int]:
        """A snapshot of the send counters."""
        with self._lock:
            return dict(self.counters)

    def _count(self, name: str) -> None:
        with self._lock:
            self.counters[name] += 1

    def _write_log(self, msg: can.Message) -> None:
        if self._log is not None:
            with self._lock:
                self._log.write(msg)

    def close(self) -> None:
        self._notifier.stop()
        self.bus.shutdown()
        if self._log is not None:
            self._log.stop()
