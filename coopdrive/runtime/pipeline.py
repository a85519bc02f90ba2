"""The order in which a vehicle's services see one simulation step.

Within a lockstep step a service sees what services earlier in this order published in the
same step, and what later services published in the previous step (their feedback). Messages
therefore flow sensor -> estimate -> decision -> command within one step, and every cycle of
the graph (planner -> v2x -> planner) is cut by exactly one step of delay.
"""

from coopdrive.bus.services import SERVICES, WORLD_SERVICE, service_entry

PIPELINE_RANK: dict[str, int] = {entry.name: entry.pipeline_rank for entry in SERVICES}
LOCKSTEP_SERVICES = tuple(entry.name for entry in SERVICES if entry.lockstep)

__all__ = ["LOCKSTEP_SERVICES", "PIPELINE_RANK", "WORLD_SERVICE", "participant_name", "rank_of", "split_participant"]


def rank_of(service: str) -> int:
    return service_entry(service).pipeline_rank


def participant_name(vehicle_id: str, service: str) -> str:
    return f"{vehicle_id}/{service}"


def split_participant(participant: str) -> tuple[str, str]:
    vehicle_id, _, service = participant.partition("/")
    return vehicle_id, service
