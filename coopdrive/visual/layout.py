"""The Foxglove layout of a drive, built with the Foxglove SDK's layout types (foxglove.layouts): the map with the
ego estimate, raw GNSS fixes and V2X stations; the 3D view of what the vehicle perceived; plots of speed, gap and
command; the planner's and actuation's states. One vehicle's topics (default "ego", the desk's and a car's).

    python -m coopdrive.visual.layout [--vehicle ID] > docs/foxglove-layout.json

docs/foxglove-layout.json is this output for "ego" (a test keeps it current); import it in Foxglove with
Layouts -> Import from file.
"""

from __future__ import annotations

import argparse
import json
import sys

import foxglove.layouts as fl

from coopdrive.bus.keys import KeyLayout
from coopdrive.visual.channels import GROUND_TRUTH_TOPIC, MAP_TOPIC, TRANSFORMS_TOPIC, vehicle_topic
from coopdrive.visual.primitives import MAP_FRAME

MAP_ZOOM_LEVEL = 17


def _path(vehicle_id: str, topic: str, field_name: str) -> str:
    return f"{KeyLayout().topic(vehicle_id, topic)}.{field_name}"


def _plot(title: str, vehicle_id: str, series: list[tuple[str, str, str]]) -> fl.PlotPanel:
    """series: (topic, field, label)."""
    return fl.PlotPanel(title=title, config=fl.PlotConfig(
        paths=[fl.PlotSeries(value=_path(vehicle_id, topic, field_name), label=label, enabled=True,
                             timestamp_method="receiveTime") for topic, field_name, label in series],
        show_legend=True))


def _column(*panels) -> fl.SplitContainer:
    return fl.SplitContainer(direction="column", items=[fl.SplitItem(content=panel) for panel in panels])


def drive_layout(vehicle_id: str = "ego") -> fl.Layout:
    fixes = [vehicle_topic(vehicle_id, name) for name in ("ego", "gnss", "v2x_stations")]
    map_panel = fl.MapPanel(title="Map", config=fl.MapConfig(
        follow_topic=fixes[0], zoom_level=MAP_ZOOM_LEVEL,
        topic_config={**{topic: fl.MapTopicSettings(history_mode="previous", time_window_seconds=30.0,
                                                    show_heading=topic == fixes[0]) for topic in fixes},
                      # The intersections' lanes as they stand now: the newest message only.
                      vehicle_topic(vehicle_id, "signals"): fl.MapTopicSettings(history_mode="none")}))
    scene_topics = [vehicle_topic(vehicle_id, "scene"), GROUND_TRUTH_TOPIC, MAP_TOPIC]
    three_dee = fl.ThreeDeePanel(title="3D", config=fl.ThreeDeeConfig(
        follow_tf=vehicle_id, fixed_frame=MAP_FRAME, follow_mode="follow-heading",
        topics={topic: fl.BaseRendererSceneUpdateTopicSettings(visible=True) for topic in scene_topics}))
    states = fl.StateTransitionsPanel(title="Planner and actuation", config=fl.StateTransitionsConfig(paths=[
        fl.StateTransitionsSeries(value=_path(vehicle_id, "planner/state", "state"), label="planner",
                                  timestamp_method="receiveTime"),
        fl.StateTransitionsSeries(value=_path(vehicle_id, "actuation/status", "mode"), label="actuation",
                                  timestamp_method="receiveTime")]))
    plots = _column(
        _plot("Speed (m/s)", vehicle_id, [("ego/state", "speed_mps", "speed"),
                                          ("control/command", "cruise_speed_mps", "cruise speed")]),
        _plot("Gap (m)", vehicle_id, [("control/command", "gap_m", "gap"),
                                      ("control/command", "desired_gap_m", "desired gap")]),
        _plot("Command (m/s2)", vehicle_id, [("control/command", "accel_request_mps2", "accel request"),
                                             ("ego/state", "accel_mps2", "accel")]),
        states)
    return fl.Layout(content=fl.SplitContainer(direction="row", items=[
        fl.SplitItem(proportion=1, content=_column(map_panel, three_dee)),
        fl.SplitItem(proportion=1, content=plots)]))


def layout_topics(layout_json: str) -> set[str]:
    """Every topic a layout names (map and 3D topics, and the topics of plot and state paths)."""
    found: set[str] = {TRANSFORMS_TOPIC}  # the 3D panel reads the frame transforms of every topic
    def visit(node) -> None:
        if isinstance(node, dict):
            for key, value in node.items():
                if key in ("topics", "topicConfig"):
                    found.update(value)
                elif key == "followTopic":
                    found.add(value)
                elif key == "value" and isinstance(value, str):
                    found.add(value.rsplit(".", 1)[0])
                visit(value)
        elif isinstance(node, list):
            for item in node:
                visit(item)
    visit(json.loads(layout_json))
    return found


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(prog="python -m coopdrive.visual.layout", description=__doc__.split("\n")[0])
    parser.add_argument("--vehicle", default="ego")
    args = parser.parse_args(argv)
    sys.stdout.write(json.dumps(json.loads(drive_layout(args.vehicle).to_json()), indent=2) + "\n")
    return 0


if __name__ == "__main__":
    sys.exit(main())
