"""The desk's stack (docker compose --profile desk, make desk): the follow scenario's stack as `coopdrive run
follow` configures it, paced to the wall clock, without the hardware-shaped links of a lockstep run.

The desk's simulator publishes each receiver's fixes on gnss/fix (no NMEA pty to find) and runs no radio box,
so the stack has no v2x service; its actuation watchdog is more patient. `python -m coopdrive.launch.desk`
prints deploy/desk/stack.json, and a test checks the file is what this gives.
"""

from __future__ import annotations

import json
import tempfile
from pathlib import Path

from coopdrive.launch.run import RunOptions, build_specs

DESK_SCENARIO = "follow"
# On a shared laptop paced to the wall clock a control command may come late by more than a car allows:
# the desk's actuation watchdog waits 0.5 s instead of 0.1 s before a safe stop.
DESK_OVERRIDES = {"actuation": {"actuator": {"watchdog": {"command_timeout_s": 0.5}}}}
NOT_AT_THE_DESK = ("sim", "v2x")
# The GNSS pty of a lockstep run and how it is read: the desk's receiver is the gnss/fix topic.
LOCKSTEP_GEOLOCATION_KEYS = ("gnss_port", "serial_sync")


def desk_stack() -> list[dict]:
    stack = []
    with tempfile.TemporaryDirectory(prefix="coopdrive-desk-") as run_dir:  # the lockstep run's files: not kept
        specs = build_specs(RunOptions(scenario=DESK_SCENARIO, service_overrides=DESK_OVERRIDES), Path(run_dir))
    for spec in specs:
        if spec.service in NOT_AT_THE_DESK:
            continue
        config = spec.config
        if spec.service == "geolocation":
            config = {key: value for key, value in config.items() if key not in LOCKSTEP_GEOLOCATION_KEYS}
        stack.append({"service": spec.service, "vehicle": spec.vehicle_id, "config": config})
    return stack


if __name__ == "__main__":
    print(json.dumps(desk_stack(), indent=2))
