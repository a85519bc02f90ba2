"""RunnerDiagnostics: what a running service tells about itself: its counters each DIAGNOSTICS_PERIOD_S on
diagnostics/<service>, its ServiceInfo to whoever asks, and its periodic handlers that fail or run late, in its log."""

from __future__ import annotations

import logging
import os
import time
from typing import Callable

from google.protobuf.message import Message

from coopdrive.bus import Bus
from coopdrive.bus.bus_mode import MTLS
from coopdrive.runtime.service import Service
from coopdrive.runtime.timers import TriggerSet
from coopdrive.v1 import diagnostics_pb2

DIAGNOSTICS_PERIOD_S = 1.0
# A periodic handler that keeps failing logs its traceback on the first and then every this many failures.
TRIGGER_FAILURE_LOG_EVERY = 500


class RunnerDiagnostics:
    def __init__(self, service_name: str, vehicle_id: str, log: logging.Logger, bus: Bus):
        self._service_name = service_name
        self._vehicle_id = vehicle_id
        self._log = log
        self._bus = bus
        self._trigger_failures: dict[str, int] = {}
        self._started_monotonic = time.monotonic()
        # Set by the runner once the service and its context exist.
        self.service: Service | None = None
        self.stopping: Callable[[], bool] = lambda: False
        self.own_cpu_s: Callable[[], float] = time.thread_time

    def on_trigger_error(self, trigger, error: Exception) -> None:
        """Counted every time; the traceback is logged the first time and then every so often, not at 50 Hz."""
        self.service.count("handler_errors")
        name = getattr(trigger.handler, "__qualname__", repr(trigger.handler))
        failures = self._trigger_failures[name] = self._trigger_failures.get(name, 0) + 1
        if failures == 1 or failures % TRIGGER_FAILURE_LOG_EVERY == 0:
            self._log.error("periodic %s failed (%d times)", name, failures, exc_info=error)

    def on_trigger_overrun(self, trigger, missed: int) -> None:
        """Logged the first time a trigger misses periods and then every so often; counted in diagnostics."""
        if trigger.overruns == missed or trigger.overruns // TRIGGER_FAILURE_LOG_EVERY > \
                (trigger.overruns - missed) // TRIGGER_FAILURE_LOG_EVERY:
            self._log.warning("periodic %s ran late: %d period(s) of %.3f s missed (%d so far)", trigger.name, missed,
                              trigger.period_s, trigger.overruns)

    def message(self, triggers: TriggerSet) -> diagnostics_pb2.Diagnostics:
        """The service's counters, the bus's errors, the triggers' overruns and the worker's CPU."""
        # How its session reaches the others: "bus mtls" (authenticated), "bus plain-loopback" or "bus plain".
        message = diagnostics_pb2.Diagnostics(level=diagnostics_pb2.HEALTH_LEVEL_OK, message=f"bus {self._bus.mode}")
        for name, value in self.service.counters.items():
            message.counters[name] = value
        message.counters["bus_decode_errors"] = self._bus.decode_errors
        message.counters["bus_callback_errors"] = self._bus.callback_errors
        message.counters["bus_authenticated"] = 1.0 if self._bus.mode == MTLS else 0.0
        for name, overruns in triggers.overruns().items():
            message.counters[f"overruns_{name}"] = overruns
        # CPU the service's own worker thread has used (handlers and triggers): where a run's time goes.
        message.counters["worker_cpu_s"] = self.own_cpu_s()
        return message

    def service_info(self) -> Message:
        return diagnostics_pb2.ServiceInfo(
            service=self._service_name, vehicle_id=self._vehicle_id,
            state="stopping" if self.stopping() else "running",
            config_json=self.service.config.model_dump_json(),
            uptime_s=time.monotonic() - self._started_monotonic, pid=os.getpid())
