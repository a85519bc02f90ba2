"""VehicleBusInput: where a service's vehicle CAN frames come from, and who puts the car's bus on can/vehicle.

In simulation the simulator publishes each step's frames on the can/vehicle topic as they would be on the bus.
On the vehicle, one service owns the car's bus: actuation (it sends the commands) opens the CAN interface and
publishes every frame it reads on can/vehicle, in batches, each frame stamped on arrival; geolocation and scene
subscribe to can/vehicle exactly as in simulation, unless their config names a CAN port of their own. Under
replay (ctx.opens_hardware is false) no port is opened: the frames come from the recorded can/vehicle.

Frames on can/vehicle stamped on another time base than the service's clock (a candump log played through the
`coopdrive` python-can interface keeps the log's times) are restamped on arrival, not dropped as too old.
"""

from __future__ import annotations

import can

from coopdrive.bus import Envelope
from coopdrive.can.bus_reader import VehicleBusReader
from coopdrive.can.vehicle_port import VehicleCanPort, VehicleCanPortConfig
from coopdrive.can.wire import VEHICLE_BUS_TOPIC, to_protobuf
from coopdrive.v1 import vehicle_pb2

# A frame stamped further than this from the service's clock was stamped on another time base (a log's): far
# beyond a batch's span or any transport delay (a replayed batch keeps its frames' times), far below the gap
# between a logger's clock and the wall clock.
FOREIGN_TIME_BASE_S = 10.0


class VehicleBusInput:
    def __init__(self, ctx, reader: VehicleBusReader, port_config: VehicleCanPortConfig | None,
                 owns_bus: bool = False) -> None:
        """ctx: the service's context (subscribe, publish, every, call_soon, now_s, opens_hardware).
        owns_bus: this service publishes what its port reads on can/vehicle unless the port config says
        otherwise (one publisher per vehicle). Raises VehicleCanPortError when the interface cannot be opened."""
        self.ctx = ctx
        self.reader = reader
        self.port: VehicleCanPort | None = None
        self._outbox: list[vehicle_pb2.CanFrame] = []
        if port_config is None or not ctx.opens_hardware:
            ctx.subscribe(VEHICLE_BUS_TOPIC, self.on_frames)
            return
        publish = port_config.publish_frames if port_config.publish_frames is not None else owns_bus
        # Frames arrive on python-can's receive thread; the reader runs on the service's worker thread.
        self.port = VehicleCanPort(port_config, lambda msg: ctx.call_soon(lambda: self._on_port_frame(msg)),
                                   clock=ctx.now_s)
        self._publishing = publish
        if publish:
            ctx.every(port_config.publish_period_s, self._publish)

    def on_frames(self, envelope: Envelope) -> None:
        now_s = self.ctx.now_s()
        for frame in envelope.message.frames:
            if abs(frame.timestamp_s - now_s) > FOREIGN_TIME_BASE_S:
                frame.timestamp_s = now_s
                self.reader.counters["can_frames_restamped"] += 1
            self.reader.feed(frame)

    def _on_port_frame(self, msg: can.Message) -> None:
        self.reader.feed(msg)
        if self._publishing:
            self._outbox.append(to_protobuf(msg))

    def _publish(self, now_s: float) -> None:
        if not self._outbox:
            return
        batch = vehicle_pb2.CanFrames(frames=self._outbox)
        self._outbox = []
        self.ctx.publish(VEHICLE_BUS_TOPIC, batch, sample_time_s=batch.frames[0].timestamp_s)
        self.reader.counters["can_frames_published"] += len(batch.frames)

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
