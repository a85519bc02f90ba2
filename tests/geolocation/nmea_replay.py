"""Replays an NMEA log through the geolocation service as `coopdrive replay` does a recording of gnss/nmea:
the log's chunks (stamped with the receiver's UTC, services/geolocation/nmea_log.py) go to the service's
gnss/nmea handler in a ReplayContext, and its 50 Hz estimate runs in between, on the chunks' clock."""

from __future__ import annotations

from dataclasses import dataclass
from pathlib import Path

from coopdrive.bus import Envelope
from coopdrive.recording.replay import ReplayContext
from coopdrive.services.geolocation.nmea_log import read_nmea_log
from coopdrive.services.geolocation.service import GeolocationConfig, GeolocationService
from coopdrive.v1 import ego_pb2, gnss_pb2

TAIL_S = 1.0  # estimates after the last chunk


@dataclass
class NmeaReplay:
    service: GeolocationService
    states: list[ego_pb2.EgoState]
    fixes: list[gnss_pb2.GnssFix]  # what the service published on ego/gnss

    def state_at_or_after(self, time_s: float) -> ego_pb2.EgoState | None:
        return next((s for s in self.states if s.header.sample_time_s >= time_s - 1e-9), None)

    @property
    def position_fixes(self) -> list[gnss_pb2.GnssFix]:
        return [f for f in self.fixes if f.fix_mode not in (gnss_pb2.FIX_MODE_UNSPECIFIED, gnss_pb2.FIX_MODE_NO_FIX)]


def nmea_chunks(data: bytes, start_s: float = 0.0, period_s: float = 0.1) -> list[tuple[float, bytes]]:
    """Bytes cut into one chunk per line, period_s apart (for tests with hand-made sentences)."""
    return [(start_s + k * period_s, line) for k, line in enumerate(data.splitlines(keepends=True))]


def replay_chunks(chunks: list[tuple[float, bytes]], config: GeolocationConfig | None = None,
                  vehicle_id: str = "ego") -> NmeaReplay:
    ctx = ReplayContext(vehicle_id=vehicle_id, service_name="geolocation")
    service = GeolocationService(config or GeolocationConfig(), ctx)
    service.start()
    period_s = 1.0 / service.config.output_rate_hz
    handlers = [handler for _, handler in ctx.handlers["gnss/nmea"]]
    start_s, end_s = chunks[0][0], chunks[-1][0] + TAIL_S
    steps = int(round((end_s - start_s) / period_s)) + 1
    next_chunk = 0
    for step in range(steps):
        now_s = start_s + step * period_s
        while next_chunk < len(chunks) and chunks[next_chunk][0] <= now_s + 1e-9:
            time_s, data = chunks[next_chunk]
            ctx.clock.set(time_s)
            chunk = gnss_pb2.NmeaChunk(data=data, port="log")
            chunk.header.sample_time_s = time_s
            for handler in handlers:
                handler(Envelope(vehicle_id, "gnss/nmea", chunk))
            next_chunk += 1
        ctx.clock.set(now_s)
        ctx.triggers.run_due(now_s)
    service.stop()
    states = [m for topic, m in ctx.outputs if topic.endswith("/ego/state")]
    fixes = [m for topic, m in ctx.outputs if topic.endswith("/ego/gnss")]
    return NmeaReplay(service, states, fixes)


def replay_nmea_log(path: str | Path, config: GeolocationConfig | None = None) -> NmeaReplay:
    return replay_chunks(read_nmea_log(path).chunks, config)
