"""Radio faults the simulator carries out itself: a silent transmitter, and lost protocol-step iCLCMs.

PartnerSilent keeps everything a vehicle sends off the air while it lasts. IclcmDrop loses the first `count`
iCLCMs a vehicle sends with a given protocol field set (one run per protocol step shows that no single lost
message deadlocks the manoeuvre), or every one for `duration_s` from the first (the step really lost). Secured packets are looked into through `unwrap` (the run's PKI).
"""

from __future__ import annotations

from collections.abc import Callable, Sequence

from coopdrive.services.sim.fault_config import Fault, IclcmDrop, PartnerSilent
from coopdrive.v2x.its_pdu import ItsMessageId
from coopdrive.v2x.packet import decode_packet
from coopdrive.v2x.reasons import V2xDecodeError

Unwrap = Callable[[bytes], bytes | None]


class RadioFaults:
    def __init__(self, faults: Sequence[Fault], unwrap: Unwrap | None = None) -> None:
        self.silences = [f for f in faults if isinstance(f, PartnerSilent)]
        self.drops = [f for f in faults if isinstance(f, IclcmDrop)]
        self._left = {id(f): f.count or 1 for f in self.drops if f.duration_s is None}
        # Per duration fault: when its window of losses ends, once the first flagged iCLCM opened it.
        self._window_end_s: dict[int, float] = {}
        self.unwrap = unwrap
        self.silenced_count = 0
        self.dropped_count = 0

    def keeps(self, sender_id: str, packet: bytes, now_s: float) -> bool:
        """False when this transmission never reaches the air."""
        if any(f.vehicle_id == sender_id and f.active(now_s) for f in self.silences):
            self.silenced_count += 1
            return False
        drops = [f for f in self.drops if f.vehicle_id == sender_id and f.active(now_s) and self._armed(f, now_s)]
        if not drops:
            return True
        content = self._iclcm(packet)
        if content is None:
            return True
        for fault in drops:
            if getattr(content, fault.flag.value):
                self._spend(fault, now_s)
                self.dropped_count += 1
                return False
        return True

    def _armed(self, fault: IclcmDrop, now_s: float) -> bool:
        if fault.duration_s is None:
            return self._left[id(fault)] > 0
        return now_s < self._window_end_s.get(id(fault), now_s + fault.duration_s)

    def _spend(self, fault: IclcmDrop, now_s: float) -> None:
        if fault.duration_s is None:
            self._left[id(fault)] -= 1
        else:
            self._window_end_s.setdefault(id(fault), now_s + fault.duration_s)

    def _iclcm(self, packet: bytes):
        if self.unwrap is not None:
            packet = self.unwrap(packet)
        try:
            decoded = decode_packet(packet) if packet is not None else None
        except V2xDecodeError:
            return None
        if decoded is None or decoded.message_type != ItsMessageId.ICLCM:
            return None
        return decoded.content
