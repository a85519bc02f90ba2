"""FoxgloveBridge: the live bus to Foxglove through the Foxglove SDK's WebSocket server (`coopdrive foxglove`).

Every stack message goes out on its own key ("coopdrive/<vehicle>/<topic>", its coopdrive.v1 protobuf schema) and
the channels Foxglove draws (coopdrive.visual.channels) beside them, each channel advertised when its first
message arrives. The lane map is the one given, or the one the bus's geolocation service reports it runs with.
"""

from __future__ import annotations

import threading
import time

import foxglove
from google.protobuf.message import Message
from mcap_protobuf.schema import build_file_descriptor_set

from coopdrive.bus import Bus
from coopdrive.recording.live_configs import ServiceConfigCollector
from coopdrive.bus.publish_spool import is_recorded
from coopdrive.roadmap import RoadMap
from coopdrive.visual.channels import VisualChannels, recorded_road_map

SERVER_NAME = "coopdrive"


class FoxgloveBridge:
    def __init__(self, bus: Bus, port: int = 8765, host: str = "0.0.0.0", road_map: RoadMap | None = None,
                 vehicle_id: str = "*"):
        """port 0: any free port (see .port). `vehicle_id`: whose topics it serves ("*": every vehicle's)."""
        self._bus = bus
        self._context = foxglove.Context()
        self._server = foxglove.start_server(name=SERVER_NAME, host=host, port=port, context=self._context)
        self._channels: dict[str, foxglove.Channel] = {}
        self._lock = threading.Lock()
        self._visuals = VisualChannels(self._log, road_map)
        self._configs = None if road_map is not None else ServiceConfigCollector(
            bus, self._learn_config, vehicle_id)
        bus.subscribe_key(bus.layout.all_topics(vehicle_id), self._on_bus)
        if self._configs is not None:
            self._configs.start()

    @property
    def port(self) -> int:
        return self._server.port

    def _on_bus(self, key: str, message: Message) -> None:
        if not is_recorded(key):
            return
        now_ns = time.time_ns()
        with self._lock:
            self._log(key, message, now_ns)
            self._visuals.on_message(key, message, now_ns)

    def _log(self, topic: str, message: Message, time_ns: int) -> None:
        channel = self._channels.get(topic)
        if channel is None:
            schema = foxglove.Schema(name=message.DESCRIPTOR.full_name, encoding="protobuf",
                                     data=build_file_descriptor_set(type(message)).SerializeToString())
            channel = foxglove.Channel(topic, schema=schema, message_encoding="protobuf", context=self._context)
            self._channels[topic] = channel
        channel.log(message.SerializeToString(), log_time=time_ns)

    def _learn_config(self, participant: str, config_json: str) -> None:
        if participant.endswith("/geolocation"):
            road_map = recorded_road_map({participant: config_json})
            with self._lock:
                self._visuals.road_map = road_map

    def close(self) -> None:
        if self._configs is not None:
            self._configs.stop(ask_again=False)
        self._server.stop()
