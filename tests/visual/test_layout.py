"""The Foxglove layout in docs/ is the one coopdrive.visual.layout builds for the vehicle "ego"."""

import io
from contextlib import redirect_stdout
from pathlib import Path

from coopdrive.visual.layout import layout_topics, main

ROOT = Path(__file__).resolve().parents[2]


def test_the_layout_in_docs_is_current():
    out = io.StringIO()
    with redirect_stdout(out):
        assert main(["--vehicle", "ego"]) == 0
    assert (ROOT / "docs" / "foxglove-layout.json").read_text() == out.getvalue()


def test_the_layout_opens_map_3d_plots_and_the_planner_state_of_the_vehicle():
    text = (ROOT / "docs" / "foxglove-layout.json").read_text()
    for panel in ('"panelType": "Map"', '"panelType": "ThreeDee"', '"panelType": "Plot"',
                  '"panelType": "StateTransitions"'):
        assert panel in text
    assert {"foxglove/ego/ego", "foxglove/ego/scene", "coopdrive/ego/ego/state", "coopdrive/ego/control/command",
            "coopdrive/ego/planner/state"} <= layout_topics(text)
