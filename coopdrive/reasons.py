"""A refusal in words: a reason from a fixed list (to count and to test against) and what made it so (to read).

CAN and V2X decoders raise it, the watchdog stops on it, the mode manager refuses with it: each reads
"reason: detail" wherever it is shown, or the reason alone when there is nothing to add.
"""

import enum
from dataclasses import dataclass
from typing import Generic, TypeVar

Reason = TypeVar("Reason", bound=enum.Enum)


def in_words(reason: enum.Enum, detail: str = "") -> str:
    return f"{reason.value}: {detail}" if detail else reason.value


@dataclass(frozen=True)
class Reasoned(Generic[Reason]):
    """A decision's cause, kept as a value (a stop's trigger, an unmet condition)."""

    reason: Reason
    detail: str = ""

    def __str__(self) -> str:
        return in_words(self.reason, self.detail)


class ReasonedError(Exception, Generic[Reason]):
    """An input that was refused; `reason` says why, `detail` what was wrong with it."""

    def __init__(self, reason: Reason, detail: str = ""):
        super().__init__(in_words(reason, detail))
        self.reason = reason
        self.detail = detail
