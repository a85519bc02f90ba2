"""The effective config of every service on a live bus, from their `_info` queryables, for a recording's metadata.

Services may start after the recorder, or restart with another config: the bus is asked again every POLL_S
and once more when the recording ends, and the newest answer of each service is kept.
"""

from __future__ import annotations

import threading
from typing import Callable

from coopdrive.bus import Bus
from coopdrive.v1 import diagnostics_pb2

POLL_S = 2.0
QUERY_TIMEOUT_S = 1.0


class ServiceConfigCollector:
    def __init__(self, bus: Bus, on_config: Callable[[str, str], None] | None = None, vehicle_id: str = "*"):
        """on_config(participant, config JSON): called for each config first seen or changed. `vehicle_id`: whose
        services are asked ("*": every vehicle's; a vehicle's bus credentials may ask only their own)."""
        self._bus = bus
        self._vehicle_id = vehicle_id
        self._on_config = on_config
        self._lock = threading.Lock()
        self._configs: dict[str, str] = {}
        self._stop = threading.Event()
        self._thread = threading.Thread(target=self._poll, name="service-configs", daemon=True)

    def start(self) -> None:
        self._thread.start()

    def stop(self, ask_again: bool = True) -> dict[str, str]:
        """Stops polling, asks once more (ask_again) and returns {"<vehicle>/<service>": config JSON}. Without
        ask_again it returns at once, leaving a query in flight to time out on the daemon thread."""
        self._stop.set()
        if ask_again:
            self._thread.join()
            self.collect()
        with self._lock:
            return dict(self._configs)

    def collect(self) -> None:
        pattern = self._bus.layout.service_info(self._vehicle_id, "*")
        for info in self._bus.query(pattern, diagnostics_pb2.ServiceInfo, timeout_s=QUERY_TIMEOUT_S):
            if info.service and info.vehicle_id and info.config_json:
                participant = f"{info.vehicle_id}/{info.service}"
                with self._lock:
                    changed = self._configs.get(participant) != info.config_json
                    self._configs[participant] = info.config_json
                if changed and self._on_config is not None:
                    self._on_config(participant, info.config_json)

    def _poll(self) -> None:
        while not self._stop.is_set():
            self.collect()
            self._stop.wait(POLL_S)
