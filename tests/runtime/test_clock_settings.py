import pytest
from pydantic import ValidationError

from coopdrive.runtime.master import ClockConfig, ClockSettings
from coopdrive.services.sim.config import SimConfig


def test_a_misspelt_clock_setting_is_refused_not_ignored():
    with pytest.raises(ValidationError, match="stp_s"):
        ClockSettings(stp_s=0.1)


def test_the_simulator_hands_the_clock_exactly_its_configured_clock_fields():
    config = SimConfig(step_s=0.05, paced=True, realtime_factor=2.0, participants=["v1/control"])
    settings = ClockSettings(**config.model_dump(include=set(ClockConfig.model_fields)))
    assert (settings.step_s, settings.paced, settings.realtime_factor, settings.participants) == (
        0.05, True, 2.0, ["v1/control"])
    assert SimConfig().step_s == 0.02 and ClockConfig().step_s == 0.01
