"""Speed profiles of scripted vehicles."""

import pytest

from coopdrive.services.sim.speed_profiles import SinusoidSpeed


def test_a_sinusoid_with_a_hard_brake_decelerates_to_standstill_and_stays_there():
    profile = SinusoidSpeed(mean_speed_mps=22.2, amplitude_mps=2.78, frequency_hz=0.2, start_s=10, periods=6,
                            brake_at_s=45.0, brake_decel_mps2=6.0)
    assert profile.speed_at(45.0) == pytest.approx(22.2)
    assert profile.speed_at(46.0) == pytest.approx(16.2)
    assert profile.speed_at(60.0) == 0.0


def test_the_sinusoid_oscillates_around_its_mean_at_its_frequency():
    profile = SinusoidSpeed(mean_speed_mps=20.0, amplitude_mps=2.0, frequency_hz=0.2, start_s=10)
    assert profile.speed_at(5.0) == 20.0
    assert profile.speed_at(11.25) == pytest.approx(22.0)
    assert profile.speed_at(13.75) == pytest.approx(18.0)
