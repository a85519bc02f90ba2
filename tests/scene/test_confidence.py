import math

import pytest

from coopdrive.services.scene.config import SourceConfig
from coopdrive.services.scene.confidence import UNKNOWN_CONFIDENCE, FusedProperty
from coopdrive.v1 import header_pb2

LIDAR = header_pb2.SENSOR_SOURCE_LIDAR
RADAR = header_pb2.SENSOR_SOURCE_RADAR
V2V = header_pb2.SENSOR_SOURCE_V2V

CONFIGS = {
    LIDAR: SourceConfig(fade_time_s=0.5, decay_per_s=0.4, max_confidence=0.9, gain=0.5),
    RADAR: SourceConfig(fade_time_s=0.5, decay_per_s=0.4, max_confidence=0.8, gain=0.5),
    V2V: SourceConfig(fade_time_s=1.0, decay_per_s=0.2, max_confidence=0.7, gain=0.3),
}


def make(closer_bias: float = 1.0) -> FusedProperty:
    return FusedProperty(CONFIGS.__getitem__, new_data_bias=3.0, closer_bias=closer_bias)


def test_a_property_nobody_has_seen_is_unknown_with_confidence_minus_one():
    prop = make()
    assert prop.confidence(0.0) == UNKNOWN_CONFIDENCE
    assert prop.sources(0.0) == []


def test_one_reading_gives_gain_times_max_confidence():
    prop = make()
    prop.support(LIDAR, 1.0)
    assert prop.confidence(1.0) == pytest.approx(0.45)  # 0 + 0.5 * (0.9 - 0)


def test_repeated_readings_of_one_source_approach_its_ceiling_but_not_beyond():
    prop = make()
    for _ in range(3):
        prop.support(LIDAR, 1.0)
    # 0.45 -> 0.675 -> 0.7875
    assert prop.confidence(1.0) == pytest.approx(0.7875)
    for _ in range(50):
        prop.support(LIDAR, 1.0)
    assert prop.confidence(1.0) == pytest.approx(0.9)


def test_a_second_independent_source_that_agrees_boosts_the_confidence_above_either_alone():
    prop = make()
    prop.support(LIDAR, 2.0)
    prop.support(RADAR, 2.0)
    # lidar 0.45, radar 0.4: 1 - (1 - 0.45)(1 - 0.4) = 0.67
    assert prop.confidence(2.0) == pytest.approx(0.67)
    assert prop.sources(2.0) == [LIDAR, RADAR]


def test_a_poorly_matching_reading_raises_the_confidence_less():
    good, poor = make(), make()
    good.support(LIDAR, 0.0, quality=1.0)
    poor.support(LIDAR, 0.0, quality=0.2)
    assert poor.confidence(0.0) == pytest.approx(0.09)  # 0.5 * 0.2 * 0.9
    assert poor.confidence(0.0) < good.confidence(0.0)


def test_confidence_decays_exponentially_with_time_since_the_last_support():
    prop = make()
    prop.support(LIDAR, 0.0)
    assert prop.confidence(0.25) == pytest.approx(0.45 * math.exp(-0.4 * 0.25))  # 0.40718


def test_each_source_decays_at_its_own_rate():
    prop = make()
    prop.support(LIDAR, 0.0)
    prop.support(V2V, 0.0)
    lidar = 0.45 * math.exp(-0.4 * 0.4)
    v2v = 0.21 * math.exp(-0.2 * 0.4)
    assert prop.confidence(0.4) == pytest.approx(1.0 - (1.0 - lidar) * (1.0 - v2v))


def test_a_property_fades_after_its_sources_fade_time_and_withholds_its_value():
    prop = make()
    prop.update(LIDAR, 0.0, value=20.0)
    assert prop.confidence(0.5) > 0.0
    assert prop.confidence(0.51) == UNKNOWN_CONFIDENCE
    assert prop.faded(0.51)
    assert prop.valid_until_s() == pytest.approx(0.5)


def test_when_one_source_fades_the_others_keep_the_property_alive_with_lower_confidence():
    prop = make()
    prop.support(LIDAR, 0.0)
    prop.support(V2V, 0.0)
    both = prop.confidence(0.5)
    alone = prop.confidence(0.6)
    assert prop.sources(0.6) == [V2V]
    assert alone == pytest.approx(0.21 * math.exp(-0.2 * 0.6))
    assert alone < both
    assert prop.confidence(1.01) == UNKNOWN_CONFIDENCE


def test_values_blend_with_a_heavy_bias_for_new_data():
    prop = make()
    prop.update(LIDAR, 0.0, value=2.0)  # confidence 0.45
    prop.update(LIDAR, 0.0, value=1.0)
    # (0.45 * 2 + 3 * 0.9 * 1) / (0.45 + 2.7) = 3.6 / 3.15
    assert prop.value == pytest.approx(3.6 / 3.15)


def test_distance_values_lean_towards_the_closer_reading():
    plain, biased = make(), make(closer_bias=2.0)
    for prop in (plain, biased):
        prop.update(LIDAR, 0.0, value=20.0)
        prop.update(LIDAR, 0.0, value=18.0)
    # closer: weight 2 * 3 * 0.9 = 5.4 against 0.45: (0.45 * 20 + 5.4 * 18) / 5.85
    assert biased.value == pytest.approx((0.45 * 20.0 + 5.4 * 18.0) / 5.85)
    assert biased.value < plain.value


def test_a_late_reading_does_not_move_the_support_time_backwards():
    prop = make()
    prop.support(LIDAR, 1.0)
    prop.support(LIDAR, 0.8)
    assert prop.valid_until_s() == pytest.approx(1.5)


def test_readings_that_match_poorly_cannot_push_a_source_beyond_quality_times_its_ceiling():
    prop = make()
    for _ in range(60):
        prop.support(V2V, 0.0, quality=0.5)
    assert prop.confidence(0.0) == pytest.approx(0.35)  # 0.5 * 0.7
    prop.support(V2V, 0.0, quality=0.1)
    # 0.35 + 0.3 * (0.07 - 0.35)
    assert prop.confidence(0.0) == pytest.approx(0.266)


def test_a_reading_that_matches_not_at_all_does_not_keep_a_property_alive():
    prop = make()
    prop.support(LIDAR, 0.0)
    prop.support(LIDAR, 0.4, quality=0.0)
    assert prop.confidence(0.6) == UNKNOWN_CONFIDENCE
