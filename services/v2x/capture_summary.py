"""Counts over the records of `coopdrive v2x decode` (capture_decode.py): what a capture holds, at a glance."""

from __future__ import annotations

from collections import Counter, defaultdict


class DecodeSummary:
    def __init__(self):
        self.frames_by_link_type: Counter[str] = Counter()
        self.frames_by_ethertype: Counter[str] = Counter()
        self.unreadable_frames: Counter[str] = Counter()
        self.gn_packets_by_header_type: Counter[str] = Counter()
        self.messages_by_type: Counter[str] = Counter()
        self.messages_by_type_and_station: defaultdict[str, Counter[str]] = defaultdict(Counter)
        self.errors: Counter[str] = Counter()
        self.signatures: Counter[str] = Counter()
        self.trust: Counter[str] = Counter()

    def add(self, record: dict) -> None:
        self.frames_by_link_type[record["link_type"]] += 1
        self.frames_by_ethertype[record["ethertype"] or "none"] += 1
        if "unreadable" in record:
            self.unreadable_frames[record["unreadable"]] += 1
            return
        if "gn" in record:
            self.gn_packets_by_header_type[record["gn"]["header_type"]] += 1
        message = record.get("message_type")
        if message:
            self.messages_by_type[message] += 1
            station = record.get("station_id")
            self.messages_by_type_and_station[message][str(station) if station is not None else "-"] += 1
        if "error" in record:
            self.errors[record["error"]] += 1
        self._add_security(record["security"])

    def _add_security(self, security: dict) -> None:
        if not security["signed"]:
            self.signatures["unsigned"] += 1
            return
        self.signatures[{True: "verified", False: "invalid", None: "unknown"}[security["verified"]]] += 1
        self.trust[{True: "trusted", False: "untrusted", None: "unknown"}[security["trusted"]]] += 1

    def as_dict(self) -> dict:
        return {"frames_by_link_type": dict(self.frames_by_link_type),
                "frames_by_ethertype": dict(self.frames_by_ethertype),
                "unreadable_frames": dict(self.unreadable_frames),
                "gn_packets_by_header_type": dict(self.gn_packets_by_header_type),
                "messages_by_type": dict(self.messages_by_type),
                "messages_by_type_and_station": {message: dict(stations) for message, stations in
                                                 self.messages_by_type_and_station.items()},
                "errors": dict(self.errors), "signatures": dict(self.signatures), "trust": dict(self.trust)}


def _counts(counter: dict) -> str:
    return ", ".join(f"{key} {count}" for key, count in sorted(counter.items())) or "none"


def format_summary(summary: DecodeSummary) -> list[str]:
    """The summary as lines for people."""
    data = summary.as_dict()
    lines = ["summary:"]
    for key in ("frames_by_link_type", "frames_by_ethertype", "unreadable_frames", "gn_packets_by_header_type",
                "messages_by_type", "errors", "signatures", "trust"):
        lines.append(f"  {key.replace('_', ' ')}: {_counts(data[key])}")
    for message, stations in sorted(data["messages_by_type_and_station"].items()):
        lines.append(f"  {message} by station: {_counts(stations)}")
    return lines
