"""The order in which a vehicle's services see one simulation step.

Within a lockstep step a service sees what services earlier in this order published in the
same step, and what later services published in the previous step (their feedback). Messages
therefore flow sensor -> estimate -> decision -> command within one step, and every cycle of
the graph (planner -> v2x -> planner) is cut by exactly one step of delay.
"""

# The service that owns the world (simulated time, sensors, radio): first in every step.
WORLD_SERVICE = "sim"

PIPELINE_RANK: dict[str, int] = {
    WORLD_SERVICE: 0,
    "geolocation": 10,
    "v2x": 20,
    "scene": 30,
    "planner": 40,
    "control": 50,
    "actuation": 60,
    "gateway": 90,
}

# Services that take part in the lockstep barrier; the gateway only observes.
LOCKSTEP_SERVICES = tuple(name for name, rank in PIPELINE_RANK.items() if rank < 90)


def rank_of(service: str) -> int:
    try:
        return PIPELINE_RANK[service]
    except KeyError:
        raise KeyError(f"unknown service {service!r}; known: {', '.join(PIPELINE_RANK)}") from None


def participant_name(vehicle_id: str, service: str) -> str:
    return f"{vehicle_id}/{service}"


def split_participant(participant: str) -> tuple[str, str]:
    vehicle_id, _, service = participant.partition("/")
    return vehicle_id, service
