"""The real RAV4 log of shared/data/can through the geolocation service, as `coopdrive replay` would run it.

The candump log's frames go on can/vehicle in 10 ms batches (as actuation publishes them on the vehicle), each
frame with its log timestamp; the service runs in a ReplayContext whose clock follows the log.
"""

from __future__ import annotations

from dataclasses import dataclass
from functools import cache
from pathlib import Path

import can
import cantools
import numpy as np

from coopdrive.bus import Envelope
from coopdrive.can.candump import read_candump
from coopdrive.can.wire import VEHICLE_BUS_TOPIC, to_protobuf
from coopdrive.recording.replay import ReplayContext
from coopdrive.services.geolocation.service import GeolocationService
from coopdrive.v1 import ego_pb2, gnss_pb2, vehicle_pb2
from tests.shared_data import shared_file

REPOSITORY = Path(__file__).resolve().parents[2]
RAV4_ADAPTER = REPOSITORY / "deploy" / "vehicles" / "toyota_rav4_2017.yaml"
RAV4_LOG = "can/comma2k19_rav4_bus0_first20s.candump.log"
BATCH_S = 0.01
KINEMATICS = 0x024


@cache
def rav4_frames() -> tuple[can.Message, ...]:
    return tuple(read_candump(shared_file(RAV4_LOG)))


def batches(messages: list[can.Message] | tuple[can.Message, ...]) -> list[vehicle_pb2.CanFrames]:
    """The frames in bus order, cut every BATCH_S of log time."""
    out: list[vehicle_pb2.CanFrames] = []
    batch_end_s = None
    for message in messages:
        if batch_end_s is None or message.timestamp >= batch_end_s:
            out.append(vehicle_pb2.CanFrames())
            batch_end_s = message.timestamp + BATCH_S
        out[-1].frames.append(to_protobuf(message))
    return out


@dataclass
class GeolocationRun:
    states: list[ego_pb2.EgoState]
    counters: dict[str, float]

    def series(self, field: str) -> tuple[np.ndarray, np.ndarray]:
        times = np.array([s.header.sample_time_s for s in self.states])
        return times, np.array([getattr(s, field) for s in self.states])


def start_fix(time_s: float, speed_mps: float) -> gnss_pb2.GnssFix:
    """One fix at the service's default origin, heading north: somewhere for dead reckoning to start."""
    fix = gnss_pb2.GnssFix(latitude_deg=51.4758, longitude_deg=5.6247, altitude_m=20.0, speed_mps=speed_mps,
                           course_deg=0.0, fix_mode=gnss_pb2.FIX_MODE_SINGLE)
    fix.header.sample_time_s = time_s
    return fix


def run_geolocation(messages, settings: dict | None = None, first_fix_speed_mps: float | None = None
                    ) -> GeolocationRun:
    """Geolocation over these frames (the RAV4 adapter unless settings say otherwise). No GNSS, but for one
    fix after the first batch when first_fix_speed_mps is given (the filter then dead-reckons from it)."""
    config = GeolocationService.Config.model_validate({"vehicle_can": str(RAV4_ADAPTER), **(settings or {})})
    ctx = ReplayContext(vehicle_id="rav4", service_name="geolocation")
    service = GeolocationService(config, ctx)
    service.start()
    for batch in batches(messages):
        now_s = batch.frames[-1].timestamp_s
        ctx.clock.set(now_s)
        for _, handler in ctx.handlers[VEHICLE_BUS_TOPIC]:
            handler(Envelope("rav4", VEHICLE_BUS_TOPIC, batch))
        if first_fix_speed_mps is not None:
            for _, handler in ctx.handlers["gnss/fix"]:
                handler(Envelope("rav4", "gnss/fix", start_fix(now_s, first_fix_speed_mps)))
            first_fix_speed_mps = None
        ctx.triggers.run_due(now_s)
    service.stop()
    states = [message for topic, message in ctx.outputs if topic.endswith("/ego/state")]
    return GeolocationRun(states, dict(service.counters))


def ground_truth(name: str) -> np.ndarray:
    return np.genfromtxt(shared_file(f"can/{name}"), delimiter=",", names=True)


def kinematics_yaw_rate_radps() -> tuple[np.ndarray, np.ndarray]:
    """KINEMATICS.YAW_RATE as the DBC decodes it, independently of the adapter."""
    database = cantools.database.load_file(str(RAV4_ADAPTER.parent / "opendbc_toyota_new_mc_pt_generated.dbc"))
    frames = [m for m in rav4_frames() if m.arbitration_id == KINEMATICS]
    values = [database.decode_message(KINEMATICS, m.data)["YAW_RATE"] for m in frames]
    return np.array([m.timestamp for m in frames]), np.radians(values)


def held(times_s: np.ndarray, reference_times_s: np.ndarray, reference: np.ndarray) -> np.ndarray:
    """The reference's latest value at or before each time (what a receiver of its frames knows then)."""
    index = np.searchsorted(reference_times_s, times_s, side="right") - 1
    return reference[np.clip(index, 0, len(reference) - 1)]


def rms(errors: np.ndarray) -> float:
    return float(np.sqrt(np.mean(np.square(errors))))
