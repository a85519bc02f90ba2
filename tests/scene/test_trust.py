import pytest

from coopdrive.services.scene.config import TrustConfig
from coopdrive.services.scene.trust import V2vTrust

from .helpers import v2v

CONFIG = TrustConfig(initial=0.6, min_trusted=0.4, agree_m=1.5, drop_per_s=0.5, raise_per_s=0.05)


def feed(trust, start_s, end_s, disagreement_m, station=1, step_s=0.1, x_of=lambda t: 10.0 * t):
    t = start_s
    while t < end_s - 1e-9:
        trust.observe(v2v(t, station, x_of(t), 0.0, 10.0), disagreement_m, plausible=True)
        t = round(t + step_s, 9)


def test_a_new_station_starts_at_the_initial_trust_and_objects_without_a_station_count_as_fully_trusted():
    trust = V2vTrust(CONFIG)
    assert trust.trust(5) == pytest.approx(0.6)
    assert trust.trust(None) == 1.0


def test_disagreeing_for_one_second_drops_trust_by_drop_per_s():
    trust = V2vTrust(CONFIG)
    feed(trust, 0.0, 1.0, disagreement_m=3.0)
    # First message credited 0.1 s, then nine steps of 0.1 s: 0.6 - 0.5 * 1.0
    assert trust.trust(1) == pytest.approx(0.1)
    assert not trust.trusted(1)


def test_trust_comes_back_ten_times_slower_than_it_went():
    trust = V2vTrust(CONFIG)
    feed(trust, 0.0, 0.4, disagreement_m=3.0)
    low = trust.trust(1)
    feed(trust, 0.4, 1.4, disagreement_m=0.2)
    assert trust.trust(1) == pytest.approx(low + 0.05)


def test_a_station_we_cannot_check_keeps_its_trust():
    trust = V2vTrust(CONFIG)
    feed(trust, 0.0, 2.0, disagreement_m=None)
    assert trust.trust(1) == pytest.approx(0.6)


def test_a_station_that_jumps_further_than_its_speed_explains_is_implausible():
    trust = V2vTrust(CONFIG)
    trust.observe(v2v(0.0, 1, 0.0, 0.0, 10.0), None, plausible=True)
    assert trust.implausibility(v2v(0.1, 1, 1.0, 0.0, 10.0)) is None
    assert "jumped" in trust.implausibility(v2v(0.1, 1, 10.0, 0.0, 10.0))
    assert "speed" in trust.implausibility(v2v(0.1, 1, 1.0, 0.0, 120.0))
    assert "acceleration" in trust.implausibility(v2v(0.1, 1, 1.0, 0.0, 10.0, accel_mps2=30.0))


def test_two_free_space_contradictions_make_a_ghost_with_no_trust_until_our_sensors_see_it():
    trust = V2vTrust(CONFIG)
    trust.free_space_contradiction(1)
    assert trust.trust(1) == pytest.approx(0.3)
    assert not trust.is_ghost(1)
    trust.free_space_contradiction(1)
    assert trust.is_ghost(1) and trust.trust(1) == 0.0
    trust.observe(v2v(1.0, 1, 10.0, 0.0, 10.0), disagreement_m=0.2, plausible=True)
    assert not trust.is_ghost(1)
