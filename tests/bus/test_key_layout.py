"""KeyLayout: a key under the root reads back as (vehicle, topic); any other key is told apart without an exception."""

import pytest

from coopdrive.bus.keys import KeyLayout

LAYOUT = KeyLayout()


def test_a_topic_key_parses_back_to_its_vehicle_and_its_topic_with_the_topic_s_slashes_kept():
    assert LAYOUT.parse(LAYOUT.topic("f2", "can/vehicle")) == ("f2", "can/vehicle")
    assert LAYOUT.split(LAYOUT.topic("world", "clock")) == ("world", "clock")


@pytest.mark.parametrize("key", ["other/f2/scene", "coopdrive/f2", "coopdrive", "", "/coopdrive/f2/scene"])
def test_a_key_outside_the_layout_parses_to_none_and_split_names_it_in_its_error(key):
    assert LAYOUT.parse(key) is None
    with pytest.raises(ValueError, match="not under coopdrive/<vehicle>/<topic>"):
        LAYOUT.split(key)


def test_another_root_parses_only_its_own_keys():
    other = KeyLayout(root="team")
    assert other.parse("team/ego/scene") == ("ego", "scene")
    assert other.parse(LAYOUT.topic("ego", "scene")) is None
