"""ProcessLayout: how a run's services are spread over OS processes (`coopdrive run --processes`)."""

from __future__ import annotations

from enum import Enum


class ProcessLayout(str, Enum):
    # One process per service, as each is its own container on the vehicle.
    SERVICE = "service"
    # One process per vehicle's stack (`coopdrive group`) and one for the simulator: the default.
    VEHICLE = "vehicle"
    # The simulator and every stack in one process: each message between them stays in the process's Zenoh
    # session, but the run gets one core.
    ONE = "one"
