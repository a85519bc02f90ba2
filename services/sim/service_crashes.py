"""The scenario's service_crash faults as the clock master's outages, and their announcement to the launcher.

The simulator knows the fault schedule and simulated time, so it decides the step of each crash and restart;
the launcher owns the processes, so it carries them out (it listens on world/service_fault). The clock holds
meanwhile (ClockMaster), which keeps a crash run as deterministic as any other.
"""

from __future__ import annotations

import logging
import math
from typing import Sequence

from coopdrive.runtime.master import Outage
from coopdrive.services.sim.fault_config import Fault, ServiceCrash

log = logging.getLogger(__name__)

# A crash without end_s restarts after compose's first restart delay (restart: on-failure waits 100 ms, then
# doubles the delay for each further failure), counted in simulated time.
RESTART_BACKOFF_S = 0.1


def crashed_participants(faults: Sequence[Fault]) -> set[str]:
    """"<vehicle>/<service>" of every service a service_crash fault kills."""
    return {f"{fault.vehicle_id}/{fault.service}" for fault in faults if isinstance(fault, ServiceCrash)}


def crash_outages(faults: Sequence[Fault], participants: Sequence[str], step_s: float) -> list[Outage]:
    """One Outage per service_crash of a service that runs in this run; the others are logged and left out."""
    outages = []
    for fault in faults:
        if not isinstance(fault, ServiceCrash):
            continue
        participant = f"{fault.vehicle_id}/{fault.service}"
        if participant not in participants:
            log.warning("service_crash of %s left out: no such service runs (%s)", participant,
                        ", ".join(participants))
            continue
        crash_step = max(1, round(fault.start_s / step_s))
        restart_s = fault.end_s if math.isfinite(fault.end_s) else fault.start_s + RESTART_BACKOFF_S
        outages.append(Outage(participant, crash_step, max(crash_step + 1, round(restart_s / step_s))))
    return outages
