"""Pseudonym change in the running service: a new ticket, station id and MAC together, on a period, never while a
manoeuvre needs partners to keep recognising us.

    changer = PseudonymChanger(signer, transmitter, reception)
    ctx.every(period_s, lambda now_s: changer.request())
    changer.change_if_due(now_s)        # before our packets of this step are built

A change that falls due during a manoeuvre waits until it is over (counted in `deferred`).
"""

from __future__ import annotations

import logging

from coopdrive.services.v2x.reception import OwnIdentity, Reception
from coopdrive.v2x.security.signer import PseudonymChangeRefused, SecuredPacketSigner
from coopdrive.services.v2x.transmission import Transmitter
from coopdrive.v1 import planner_pb2

log = logging.getLogger(__name__)


def manoeuvre_in_progress(behaviour: planner_pb2.BehaviourRequest | None, denms_active: bool) -> str | None:
    """Why our identity must hold now, or None: partners of a platoon, merge or intersection protocol know us by
    station id (forward_id, backward_id, the merge flags), and a DENM's action id carries our station id."""
    if denms_active:
        return "a DENM of ours is being repeated"
    if behaviour is None:
        return None
    intent = behaviour.iclcm
    if intent.forward_id or intent.backward_id or intent.platoon_id:
        return "paired with partners (platoon or merge)"
    if intent.acknowledge or intent.merge_request or intent.safe_to_merge or intent.merge_flag or \
            intent.merge_flag_head or intent.merge_flag_tail or intent.counter_intersection:
        return "an iCLCM protocol step is under way"
    return None


class PseudonymChanger:
    def __init__(self, signer: SecuredPacketSigner, transmitter: Transmitter, reception: Reception):
        self.signer, self.transmitter, self.reception = signer, transmitter, reception
        self.due = False
        self.changes = 0
        self.deferred = 0
        self.refused = 0

    def request(self) -> None:
        self.due = True

    def change_if_due(self, now_s: float) -> bool:
        """True when the pseudonym changed now."""
        if not self.due:
            return False
        holding = manoeuvre_in_progress(self.transmitter.iclcm.behaviour, bool(self.transmitter.denm.active))
        if holding is not None:
            self.deferred += 1
            return False
        self.due = False
        old = self.signer.identity
        try:
            new = self.signer.rotate_pseudonym()
        except PseudonymChangeRefused as error:
            self.refused += 1
            log.warning("pseudonym change refused: %s", error)
            return False
        self.transmitter.use_identity(new.station_id, new.mac)
        self.reception.own = OwnIdentity(new.mac, new.station_id)
        self.changes += 1
        log.info("pseudonym changed at %.2f s: station id %d -> %d, ticket %s -> %s", now_s, old.station_id,
                 new.station_id, old.ticket.digest.hex(), new.ticket.digest.hex())
        return True
