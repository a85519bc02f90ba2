"""Interchangeable laws keep one contract each, so the controllers never ask which law they hold."""

import inspect

import pytest

from coopdrive.services.control.lateral.pd import HeudiasycPd
from coopdrive.services.control.lateral.pure_pursuit import PurePursuit
from coopdrive.services.control.lateral.stanley import Stanley
from coopdrive.services.control.lateral.types import SteeringLaw
from coopdrive.services.control.longitudinal.acc import RadarAcc, RajamaniAcc
from coopdrive.services.control.longitudinal.cacc import LagCompensatedCacc
from coopdrive.services.control.longitudinal.contracts import CruiseLaw, FollowingLaw
from coopdrive.services.control.longitudinal.cruise import CruisePi
from coopdrive.services.control.longitudinal.dcacc import Dcacc
from coopdrive.services.control.longitudinal.drivertive import DrivertiveSpeed
from coopdrive.services.control.longitudinal.ploeg import PloegCacc
from coopdrive.services.control.profiles import CAR


def contract_methods(protocol) -> dict[str, list[str]]:
    return {name: list(inspect.signature(member).parameters)
            for name, member in vars(protocol).items() if inspect.isfunction(member) and not name.startswith("_")}


def assert_keeps(law_class, protocol) -> None:
    for name, parameters in contract_methods(protocol).items():
        method = getattr(law_class, name, None)
        assert method is not None, f"{law_class.__name__} has no {name}"
        assert list(inspect.signature(method).parameters) == parameters, f"{law_class.__name__}.{name}"


@pytest.mark.parametrize("law", [LagCompensatedCacc, PloegCacc, Dcacc, RadarAcc, RajamaniAcc])
def test_every_following_law_takes_the_same_reset_and_step(law):
    assert_keeps(law, FollowingLaw)


@pytest.mark.parametrize("law", [CruisePi, DrivertiveSpeed])
def test_every_cruise_law_takes_the_same_calls_and_says_whether_it_is_engaged(law):
    assert_keeps(law, CruiseLaw)
    instance = law(CAR)
    instance.engage(0.0, 10.0)
    assert instance.engaged
    instance.disengage()
    assert not instance.engaged


@pytest.mark.parametrize("law", [HeudiasycPd, Stanley, PurePursuit])
def test_every_steering_law_maps_a_path_state_to_a_wheel_angle(law):
    assert_keeps(law, SteeringLaw)
