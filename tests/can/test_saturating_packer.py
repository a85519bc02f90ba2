"""The simulator's packer gives, for every frame of vehicle.dbc, the bytes cantools encodes from the same values
saturated at the DBC ranges."""

import math

import cantools
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from coopdrive.can import frames
from coopdrive.can.frames import VehicleFrame
from coopdrive.can.saturating_packer import SaturatingPacker, saturated_values

# Values well beyond every range of the DBC, and the ones a simulated sensor can produce by accident.
values = st.one_of(st.floats(min_value=-5000.0, max_value=5000.0), st.just(math.nan), st.just(math.inf),
                   st.just(-math.inf), st.integers(min_value=-300, max_value=300))

MOTOROLA_DBC = """VERSION ""
BO_ 100 Motorola: 8 NODE
 SG_ Speed : 7|16@0+ (0.01,0) [0|655.35] "m/s" NODE
"""


@pytest.mark.parametrize("frame", list(VehicleFrame))
@settings(max_examples=200, deadline=None)
@given(data=st.data())
def test_every_frame_packs_to_the_bytes_cantools_encodes_from_the_saturated_values(frame, data):
    definition = frames.message(frame)
    signals = {signal.name: data.draw(values, label=signal.name) for signal in definition.signals}
    expected = definition.encode(saturated_values(definition, signals), strict=False)
    assert bytes(SaturatingPacker(definition).pack(signals)) == expected


def test_a_negative_value_of_a_signed_signal_packs_as_its_twos_complement():
    definition = frames.message(VehicleFrame.INERTIAL)
    payload = SaturatingPacker(definition).pack({"AccelLongitudinal": -0.001, "AccelLateral": 0.0, "YawRate": 0.0,
                                                 "Counter": 0, "Checksum": 0})
    assert payload[:2] == b"\xff\xff"
    assert definition.decode(bytes(payload))["AccelLongitudinal"] == pytest.approx(-0.001)


def test_a_frame_with_a_motorola_signal_is_refused_when_the_packer_is_made():
    definition = cantools.database.load_string(MOTOROLA_DBC, database_format="dbc").get_message_by_name("Motorola")
    with pytest.raises(ValueError, match="Motorola.Speed: only little-endian integer signals"):
        SaturatingPacker(definition)
