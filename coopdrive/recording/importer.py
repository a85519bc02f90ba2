"""`coopdrive import`: a team's own logs (NMEA, candump, V2X captures) as one recording that `replay` takes.

Time base: every log keeps its own clock, in seconds (NMEA: Unix time from the receiver's UTC; pcap: the
capture's Unix time; candump: the logger's clock as written, often seconds since boot), plus the --offset given
for it. That is the time base of a recording made on the vehicle (services on the wall clock stamp Unix time), so
a replayed service sees the receiver's UTC and the arrival times agree as they did on the road. Logs on different
clocks are lined up with --offset; the summary says when they do not overlap.

The recording's metadata: the default config of each vehicle service under "coopdrive.config" (so replay knows
the vehicle and has a config to change with --set), marked as defaults under "coopdrive.config_source", and
what was imported and its time span under "coopdrive.import".
"""

from __future__ import annotations

import datetime as dt
import json
from dataclasses import dataclass, field
from pathlib import Path

from coopdrive.bus.keys import KeyLayout
from coopdrive.recording.candump_import import read_candump_log
from coopdrive.recording.import_source import ImportFailure, SourceReport, TimedMessage
from coopdrive.recording.nmea_import import read_nmea_log
from coopdrive.recording.pcap_import import read_pcap
from coopdrive.recording.replay_config import CONFIG_SOURCE_METADATA
from coopdrive.bus.publish_spool import NANOSECONDS
from coopdrive.recording.writer import McapRecorder, config_metadata
from coopdrive.runtime.registry import VEHICLE_STACK, service_class

DEFAULT_VEHICLE = "ego"
SENDER = "import"
IMPORT_METADATA = "coopdrive.import"
# The services whose default configs an import writes: the vehicle's stack and its radio.
IMPORT_CONFIG_SERVICES = VEHICLE_STACK


@dataclass
class ImportRequest:
    out: Path
    vehicle_id: str = DEFAULT_VEHICLE
    nmea: list[Path] = field(default_factory=list)
    candump: list[tuple[Path, str]] = field(default_factory=list)  # (file, bus name: can/<bus>)
    pcap: list[Path] = field(default_factory=list)
    offsets_s: dict[str, float] = field(default_factory=dict)  # nmea|candump|pcap or a file's name -> seconds
    nmea_rate_hz: float | None = None


@dataclass
class ImportResult:
    out: Path
    sources: list[SourceReport]
    messages: int
    warnings: list[str]

    def summary_lines(self) -> list[str]:
        lines = [source.summary_line() for source in self.sources]
        lines += [f"warning: {warning}" for warning in self.warnings]
        lines.append(f"wrote {self.messages} messages to {self.out}")
        return lines


def import_logs(request: ImportRequest) -> ImportResult:
    if not (request.nmea or request.candump or request.pcap):
        raise ImportFailure("nothing to import: give --nmea, --candump or --pcap")
    sources = [read_nmea_log(path, request.nmea_rate_hz) for path in request.nmea]
    sources += [read_candump_log(path, bus) for path, bus in request.candump]
    sources += [read_pcap(path) for path in request.pcap]
    _apply_offsets(sources, request.offsets_s)
    messages = sorted((m for source in sources for m in source.messages), key=lambda m: m.time_s)
    _stamp(messages, request.vehicle_id)
    recorder = McapRecorder(request.out, metadata=_metadata(request, sources))
    layout = KeyLayout()
    try:
        for item in messages:
            recorder.write(layout.topic(request.vehicle_id, item.topic), item.message,
                           log_time_ns=round(item.time_s * NANOSECONDS))
    finally:
        recorder.close()
    return ImportResult(request.out, sources, len(messages), _overlap_warnings(sources))


def _apply_offsets(sources: list[SourceReport], offsets_s: dict[str, float]) -> None:
    used = set()
    for source in sources:
        for name in (source.kind, source.path.name, str(source.path)):
            if name in offsets_s:
                source.offset_s = offsets_s[name]
                used.add(name)
        for message in source.messages:
            message.shift(source.offset_s)
    unknown = sorted(set(offsets_s) - used)
    if unknown:
        names = ", ".join(sorted({s.kind for s in sources} | {s.path.name for s in sources}))
        raise ImportFailure(f"--offset {', '.join(unknown)}: no imported log of that name (there are: {names})")


def _stamp(messages: list[TimedMessage], vehicle_id: str) -> None:
    sequences: dict[str, int] = {}
    for item in messages:
        sequences[item.topic] = sequences.get(item.topic, 0) + 1
        header = item.message.header
        header.sent_time_s = header.sample_time_s = item.time_s
        header.vehicle_id = vehicle_id
        header.sender = SENDER
        header.sequence = sequences[item.topic]


def _metadata(request: ImportRequest, sources: list[SourceReport]) -> dict[str, dict[str, str]]:
    configs = {f"{request.vehicle_id}/{name}": service_class(name).Config().model_dump_json()
               for name in IMPORT_CONFIG_SERVICES}
    start_s = min((s.first_s for s in sources if s.first_s is not None), default=None)
    imported = {
        "time_base": "each log's own seconds plus its --offset (Unix time for NMEA UTC and pcap)",
        "start_s": "" if start_s is None else repr(start_s),
        "start_utc": "" if start_s is None else dt.datetime.fromtimestamp(start_s, dt.timezone.utc).isoformat(),
        "sources": json.dumps([source.as_dict() for source in sources]),
    }
    return {**config_metadata(configs), CONFIG_SOURCE_METADATA: {key: "default" for key in configs},
            IMPORT_METADATA: imported}


def _overlap_warnings(sources: list[SourceReport]) -> list[str]:
    spans = [(s, s.first_s, s.last_s) for s in sources if s.first_s is not None]
    warnings = []
    for index, (a, a_first, a_last) in enumerate(spans):
        for b, b_first, b_last in spans[index + 1:]:
            if a_last < b_first or b_last < a_first:
                gap_s = max(b_first - a_last, a_first - b_last)
                warnings.append(f"{a.path.name} and {b.path.name} do not overlap in time ({gap_s:.1f} s apart): "
                                f"line them up with --offset NAME=SECONDS")
    for source in sources:
        if not source.messages:
            warnings.append(f"{source.path.name}: nothing imported")
    return warnings
