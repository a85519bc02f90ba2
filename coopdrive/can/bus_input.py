"""VehicleBusInput: where a service's vehicle CAN frames come from.

On the vehicle, the CAN interface itself (a VehicleCanPort, when the service's config names one); in simulation
and replay, the can/vehicle topic, on which the simulator publishes each step's frames as they would be on the
bus. Either way the frames go to the service's VehicleBusReader on the service's worker thread.
"""

from __future__ import annotations

import can

from coopdrive.bus import Envelope
from coopdrive.can.bus_reader import VehicleBusReader
from coopdrive.can.vehicle_port import VehicleCanPort, VehicleCanPortConfig
from coopdrive.can.wire import VEHICLE_BUS_TOPIC


class VehicleBusInput:
    def __init__(self, ctx, reader: VehicleBusReader, port_config: VehicleCanPortConfig | None) -> None:
        """ctx: the service's context (subscribe, call_soon, now_s). Raises VehicleCanPortError when the
        configured interface cannot be opened."""
        self.reader = reader
        self.port: VehicleCanPort | None = None
        if port_config is None:
            ctx.subscribe(VEHICLE_BUS_TOPIC, self.on_frames)
        else:
            # Frames arrive on python-can's receive thread; the reader runs on the service's worker thread.
            self.port = VehicleCanPort(port_config, lambda msg: ctx.call_soon(lambda: reader.feed(msg)),
                                       clock=ctx.now_s)

    def on_frames(self, envelope: Envelope) -> None:
        self.reader.feed_all(envelope.message)

    def send(self, frames: list[can.Message]) -> None:
        """Onto the vehicle's bus when there is one (in simulation, frames travel on the bus topics instead)."""
        if self.port is not None:
            self.port.send(frames)

    def counts(self) -> dict[str, int]:
        counts = dict(self.reader.counters)
        if self.port is not None:
            counts.update(self.port.counts())
        return counts

    def close(self) -> None:
        if self.port is not None:
            self.port.close()
