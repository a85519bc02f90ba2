"""RunMessages: what the judge scores from a run (ground truth, the stacks' ego states, fixes and scenes), by topic."""

from __future__ import annotations

import threading
from dataclasses import dataclass, field
from pathlib import Path

from google.protobuf.message import Message

from coopdrive.recording.reader import read_messages, recorded_topics
from coopdrive.v1 import ego_pb2, gnss_pb2, scene_pb2, sim_pb2, v2x_pb2

TRUTH_SUFFIX = "/ground_truth"
EGO_STATE_SUFFIX = "/ego/state"
# The receiver's fixes: as a gnss/fix topic carries them, and as geolocation decoded them from a serial port.
GNSS_FIX_SUFFIXES = ("/gnss/fix", "/ego/gnss")
SCENE_SUFFIX = "/scene"
V2X_STATUS_SUFFIX = "/v2x/status"
RESULT_SUFFIX = "/result"
# The channels add() takes messages from: a recording's others (CAN, sensors, V2X packets) are not read at all.
SCORED_SUFFIXES = (TRUTH_SUFFIX, EGO_STATE_SUFFIX, *GNSS_FIX_SUFFIXES, SCENE_SUFFIX, V2X_STATUS_SUFFIX, RESULT_SUFFIX)


def vehicle_of(topic: str) -> str:
    """The vehicle id of a key coopdrive/<vehicle>/<topic>."""
    parts = topic.split("/")
    return parts[1] if len(parts) > 2 else ""


@dataclass
class RunMessages:
    """Collects the scored messages; add() is safe from many threads (the bus observer's)."""

    truth: list[sim_pb2.GroundTruth] = field(default_factory=list)
    ego_states: dict[str, list[ego_pb2.EgoState]] = field(default_factory=dict)
    gnss_fixes: dict[str, list[gnss_pb2.GnssFix]] = field(default_factory=dict)
    scenes: dict[str, list[scene_pb2.Scene]] = field(default_factory=dict)
    # The latest v2x/status of each vehicle (its counters are cumulative).
    v2x_status: dict[str, v2x_pb2.V2xStatus] = field(default_factory=dict)
    # The simulator's world/result, when the run got that far (names the scenario).
    result: sim_pb2.RunResult | None = None
    _lock: threading.Lock = field(default_factory=threading.Lock, repr=False, compare=False)

    def add(self, topic: str, message: Message) -> None:
        with self._lock:
            if isinstance(message, sim_pb2.GroundTruth):
                self.truth.append(message)
            elif isinstance(message, ego_pb2.EgoState) and topic.endswith(EGO_STATE_SUFFIX):
                self.ego_states.setdefault(vehicle_of(topic), []).append(message)
            elif isinstance(message, gnss_pb2.GnssFix) and topic.endswith(GNSS_FIX_SUFFIXES):
                self.gnss_fixes.setdefault(vehicle_of(topic), []).append(message)
            elif isinstance(message, scene_pb2.Scene) and topic.endswith(SCENE_SUFFIX):
                self.scenes.setdefault(vehicle_of(topic), []).append(message)
            elif isinstance(message, v2x_pb2.V2xStatus) and topic.endswith(V2X_STATUS_SUFFIX):
                vehicle_id = vehicle_of(topic)
                latest = self.v2x_status.get(vehicle_id)
                if latest is None or message.header.sample_time_s >= latest.header.sample_time_s:
                    self.v2x_status[vehicle_id] = message
            elif isinstance(message, sim_pb2.RunResult) and self.result is None:
                self.result = message

    @classmethod
    def from_recording(cls, path: str | Path) -> RunMessages:
        messages = cls()
        scored = [topic for topic in recorded_topics(path) if topic.endswith(SCORED_SUFFIXES)]
        for recorded in read_messages(path, scored):
            messages.add(recorded.topic, recorded.message)
        return messages

    def sorted_truth(self) -> list[sim_pb2.GroundTruth]:
        """Truth in sample-time order, one message per sample time (Zenoh keeps no order across threads)."""
        by_time: dict[float, sim_pb2.GroundTruth] = {}
        with self._lock:
            for message in self.truth:
                by_time.setdefault(message.header.sample_time_s, message)
        return [by_time[t] for t in sorted(by_time)]
