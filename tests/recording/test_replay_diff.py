"""The difference report: outputs paired by sample time, numeric fields by largest and RMS difference."""

import math

import pytest

from coopdrive.recording.replay_diff import compare_outputs, table
from coopdrive.v1 import ego_pb2

TOPIC = "coopdrive/ego/ego/state"


def state(time_s: float, x_m: float, heading_rad: float = 0.0, mode=ego_pb2.LOCALISATION_MODE_GNSS_PRECISE,
          sequence: int = 1) -> tuple[str, ego_pb2.EgoState]:
    message = ego_pb2.EgoState(x_m=x_m, heading_rad=heading_rad, mode=mode)
    message.header.sample_time_s, message.header.sent_time_s, message.header.sequence = time_s, time_s, sequence
    return TOPIC, message


def test_outputs_a_few_ms_apart_are_paired_and_only_the_fields_that_moved_are_named():
    recorded = [state(10.0 + 0.02 * k + 0.003, x_m=float(k)) for k in range(50)]
    replayed = [state(10.0 + 0.02 * k, x_m=float(k) + (0.3 if k == 7 else 0.1)) for k in range(50)]
    [difference] = compare_outputs(replayed, recorded)
    assert (difference.recorded, difference.replayed, difference.paired) == (50, 50, 50)
    assert [f.name for f in difference.moved()] == ["x_m"]
    x = difference.numeric["x_m"]
    assert x.max_abs == pytest.approx(0.3)
    assert x.rms == pytest.approx(math.sqrt((49 * 0.01 + 0.09) / 50))
    assert "ego/ego/state" in table([difference]) and "max |diff| 0.3" in table([difference])


def test_headings_either_side_of_a_half_turn_differ_by_their_angle_and_a_changed_mode_is_counted():
    recorded = [state(1.0, 0.0, heading_rad=math.pi - 0.01), state(2.0, 0.0)]
    replayed = [state(1.0, 0.0, heading_rad=-math.pi + 0.01), state(2.0, 0.0, mode=ego_pb2.LOCALISATION_MODE_LOST)]
    [difference] = compare_outputs(replayed, recorded)
    assert difference.numeric["heading_rad"].max_abs == pytest.approx(0.02)
    assert difference.other["mode"].differing == 1


def test_an_output_without_a_partner_in_time_is_counted_but_not_paired_and_diagnostics_are_left_out():
    recorded = [state(1.0, 0.0), state(2.0, 0.0), state(3.0, 0.0)]
    replayed = [state(1.0, 0.0), state(4.0, 5.0)]  # 4.0 is more than half a spacing from 3.0
    diagnostics = ("coopdrive/ego/diagnostics/geolocation", ego_pb2.EgoState())
    differences = compare_outputs(replayed + [diagnostics], recorded)
    assert [(d.topic, d.recorded, d.replayed, d.paired) for d in differences] == [("ego/ego/state", 3, 2, 1)]
    assert differences[0].moved() == []
