import dataclasses
import enum

import pytest

from coopdrive.can.frames import CanDecodeError, DecodeFailure
from coopdrive.reasons import Reasoned, ReasonedError
from coopdrive.services.actuation.watchdog import StopCause, StopTrigger
from coopdrive.v2x.reasons import RejectReason, V2xDecodeError


class Why(enum.Enum):
    LATE = "too late"


def test_a_reason_reads_with_its_detail_after_a_colon_and_alone_without_one():
    assert str(Reasoned(Why.LATE, "0.2 s")) == "too late: 0.2 s"
    assert str(Reasoned(Why.LATE)) == "too late"
    assert str(ReasonedError(Why.LATE, "0.2 s")) == "too late: 0.2 s"
    assert str(ReasonedError(Why.LATE)) == "too late"


def test_a_kept_reason_is_a_value_that_cannot_be_changed():
    trigger = StopTrigger(StopCause.SERVICE_DEAD, "planner")
    assert trigger == StopTrigger(StopCause.SERVICE_DEAD, "planner")
    assert trigger != Reasoned(StopCause.SERVICE_DEAD, "planner")
    with pytest.raises(dataclasses.FrozenInstanceError):
        trigger.detail = "control"


def test_an_error_keeps_its_reason_and_detail_and_the_kind_its_callers_catch():
    error = CanDecodeError(DecodeFailure.BAD_CHECKSUM, "0x3f")
    assert (error.reason, error.detail, str(error)) == (DecodeFailure.BAD_CHECKSUM, "0x3f", "bad checksum: 0x3f")
    assert isinstance(error, ValueError)
    assert not isinstance(V2xDecodeError(RejectReason.INVALID_SIGNATURE), ValueError)
