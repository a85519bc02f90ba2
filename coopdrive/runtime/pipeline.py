"""The order in which a vehicle's services see one simulation step.

Within a lockstep step a service sees what services earlier in this order published in the
same step, and what later services published in the previous step (their feedback). Messages
therefore flow sensor -> estimate -> decision -> command within one step, and every cycle of
the graph (planner -> v2x -> planner) is cut by exactly one step of delay.
"""

from coopdrive.bus.services import SERVICES, WORLD_SERVICE, service_entry

PIPELINE_RANK: dict[str, int] = {entry.name: entry.pipeline_rank for entry in SERVICES}
LOCKSTEP_SERVICES = tuple(entry.name for entry in SERVICES if entry.lockstep)

__all__ = ["LOCKSTEP_SERVICES", "PIPELINE_RANK", "WORLD_SERVICE", "participant_name", "rank_of", "split_participant",
           "step_order"]
# A sender outside the table (a tool, an import) comes after every service of the step.
UNRANKED = 99


def step_order(header, topic: str, vehicle_id: str) -> tuple:
    """Where a message falls among the messages sent in its step: by its sender's place in the pipeline, then by
    key and sequence. The dispatcher hands a service a step's inputs in this order, and the visual channels draw
    in it, so neither depends on the order in which messages arrived."""
    return PIPELINE_RANK.get(header.sender, UNRANKED), topic, vehicle_id, header.sequence


def rank_of(service: str) -> int:
    return service_entry(service).pipeline_rank


def participant_name(vehicle_id: str, service: str) -> str:
    return f"{vehicle_id}/{service}"


def split_participant(participant: str) -> tuple[str, str]:
    vehicle_id, _, service = participant.partition("/")
    return vehicle_id, service
