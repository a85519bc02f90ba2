"""CyclicSendSchedule: which frames go out this cycle, by their DBC cycle time or a changed signal."""

from collections.abc import Mapping

from coopdrive.can import frames
from coopdrive.can.frames import VehicleFrame

MS_PER_S = 1000.0
# A 20 ms frame sent from a 50 Hz loop is due on every tick despite the ticks' float rounding.
CYCLE_TOLERANCE_S = 0.0005


class CyclicSendSchedule:
    """Cyclic-and-on-change sending, as a body ECU does it: a frame goes out once its DBC cycle time
    (GenMsgCycleTime) has passed since it last went out, and at once when one of its signals changed.
    A frame without a cycle time goes out every time."""

    def __init__(self) -> None:
        # frame -> (when it last went out, the signals it carried)
        self._last_sent: dict[VehicleFrame, tuple[float, dict[str, float]]] = {}

    @staticmethod
    def cycle_time_s(frame: VehicleFrame) -> float:
        return (frames.message(frame).cycle_time or 0) / MS_PER_S

    def due(self, signals: Mapping[VehicleFrame, Mapping[str, float]], now_s: float) -> list[VehicleFrame]:
        """The frames of `signals` to send at now_s; each one returned counts as sent."""
        due = []
        for frame, values in signals.items():
            last = self._last_sent.get(frame)
            if last is None or values != last[1] or not 0.0 <= now_s - last[0] < (
                    self.cycle_time_s(frame) - CYCLE_TOLERANCE_S):
                due.append(frame)
                self._last_sent[frame] = (now_s, dict(values))
        return due
