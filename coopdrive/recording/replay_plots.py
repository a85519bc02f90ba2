"""`coopdrive replay --report DIR`: the replayed outputs drawn over the recorded ones, and the differences as JSON.

For an ego state (geolocation): the track on an x/y plot with equal axes, speed, heading and localisation mode
over time. For every other topic with fields that moved: those fields over time (up to MAX_FIELDS of them).
"""

from __future__ import annotations

import json
from pathlib import Path

import matplotlib

matplotlib.use("Agg")  # files only: a replay runs on desks and in CI without a display
import matplotlib.pyplot as plt  # noqa: E402  (after the backend is chosen)

from google.protobuf.message import Message  # noqa: E402

from coopdrive.recording.flatten import flatten  # noqa: E402
from coopdrive.recording.replay_diff import TopicDifference  # noqa: E402

MAX_FIELDS = 4
EGO_STATE = "ego/state"


def write_report(directory: Path, replayed: list[tuple[str, Message]], recorded: list[tuple[str, Message]],
                 differences: list[TopicDifference], summary: dict) -> list[Path]:
    directory.mkdir(parents=True, exist_ok=True)
    written = [directory / "differences.json"]
    written[0].write_text(json.dumps(summary, indent=2))
    for difference in differences:
        mine, theirs = _rows(replayed, difference.topic), _rows(recorded, difference.topic)
        if not mine and not theirs:
            continue
        name = difference.topic.replace("/", "_")
        if difference.topic.endswith("/" + EGO_STATE):
            written.append(_ego_state_plot(directory / f"{name}.png", mine, theirs))
        elif difference.moved():
            fields = [f.name for f in difference.moved() if f.name in difference.numeric][:MAX_FIELDS]
            if fields:
                written.append(_fields_plot(directory / f"{name}.png", difference.topic, fields, mine, theirs))
    return written


def _rows(items: list[tuple[str, Message]], topic: str) -> list[dict]:
    return sorted((flatten(message) for key, message in items if key.endswith("/" + topic)),
                  key=lambda row: row["header.sample_time_s"])


def _series(rows: list[dict], name: str) -> tuple[list[float], list]:
    return [row["header.sample_time_s"] for row in rows], [row[name] for row in rows]


def _ego_state_plot(path: Path, replayed: list[dict], recorded: list[dict]) -> Path:
    figure, axes = plt.subplots(2, 2, figsize=(12, 9))
    track, speed, heading, mode = axes.flat
    t0 = min(rows[0]["header.sample_time_s"] for rows in (replayed, recorded) if rows)
    for rows, label, style in ((recorded, "recorded", "-"), (replayed, "replayed", "--")):
        if not rows:
            continue
        track.plot([r["x_m"] for r in rows], [r["y_m"] for r in rows], style, label=label)
        for axis, name in ((speed, "speed_mps"), (heading, "heading_rad"), (mode, "mode")):
            times, values = _series(rows, name)
            axis.plot([t - t0 for t in times], values, style, label=label)
    track.set(xlabel="x (m, east)", ylabel="y (m, north)", title="track")
    track.set_aspect("equal", adjustable="datalim")
    speed.set(xlabel="time (s)", ylabel="speed (m/s)", title="speed")
    heading.set(xlabel="time (s)", ylabel="heading (rad)", title="heading")
    mode.set(xlabel="time (s)", title="localisation mode")
    for axis in axes.flat:
        axis.grid(True, alpha=0.3)
        axis.legend()
    figure.tight_layout()
    figure.savefig(path, dpi=90)
    plt.close(figure)
    return path


def _fields_plot(path: Path, topic: str, fields: list[str], replayed: list[dict], recorded: list[dict]) -> Path:
    figure, axes = plt.subplots(len(fields), 1, figsize=(11, 2.6 * len(fields)), squeeze=False)
    t0 = min(rows[0]["header.sample_time_s"] for rows in (replayed, recorded) if rows)
    for axis, name in zip(axes[:, 0], fields):
        for rows, label, style in ((recorded, "recorded", "-"), (replayed, "replayed", "--")):
            times, values = _series(rows, name)
            axis.plot([t - t0 for t in times], values, style, label=label)
        axis.set(ylabel=name, title=f"{topic}: {name}")
        axis.grid(True, alpha=0.3)
        axis.legend()
    axes[-1, 0].set_xlabel("time (s)")
    figure.tight_layout()
    figure.savefig(path, dpi=90)
    plt.close(figure)
    return path
