"""`coopdrive score FILE --reference REF.csv`: a replay's ego states and the fixes it decoded, judged against a
reference trajectory (reference_score.py); a table, or JSON (printed, or written with --out). With --standstill
instead, the reference is the mean of the recording's own fixes, for a receiver that stood still throughout
(ReferenceTrack.standing)."""

from __future__ import annotations

import json
import struct
import sys
from dataclasses import dataclass
from pathlib import Path

import numpy as np
from mcap.exceptions import McapError
from rich.console import Console
from rich.table import Table

from coopdrive.exit_status import EXIT_OK, EXIT_USAGE
from coopdrive.judging.consistency import CONSISTENT_TWO_SIGMA_SHARE
from coopdrive.judging.reference_report import write_reference_report
from coopdrive.judging.reference_score import ReferenceScore, TrackSeries, score_series
from coopdrive.judging.reference_track import ReferenceTrack, compass_to_enu_rad
from coopdrive.judging.run_messages import RunMessages
from coopdrive.recording.reader import read_metadata
from coopdrive.recording.writer import CONFIG_METADATA
from coopdrive.services.geolocation.config import GeolocationConfig
from coopdrive.services.geolocation.frames import LeverArm
from coopdrive.services.geolocation.motion_models import HEADING, VEHICLE_STATE_DIM, E, N
from coopdrive.v1 import ego_pb2

POSE_ROWS = [E, N, HEADING]


STANDING_REFERENCE = "the mean of its fixes (standing still)"


@dataclass(frozen=True)
class ReferenceRequest:
    recording: Path
    reference: Path | None  # None: standing, against the mean of the recording's fixes
    vehicle_id: str = "ego"
    lever_arm: LeverArm | None = None  # None: the recorded geolocation config's antenna
    max_offset_s: float = 0.5
    out: Path | None = None
    as_json: bool = False
    report: Path | None = None  # a folder for the report page

    @property
    def reference_name(self) -> str:
        return STANDING_REFERENCE if self.reference is None else self.reference.name


def recorded_antenna(recording: Path, vehicle_id: str) -> LeverArm:
    """The GNSS antenna of the geolocation config the recording holds for the vehicle (its keys, else its car's
    file, else the default; no config: the rear axle)."""
    config = read_metadata(recording).get(CONFIG_METADATA, {}).get(f"{vehicle_id}/geolocation")
    if config is None:
        return LeverArm()
    return LeverArm(*GeolocationConfig.model_validate_json(config).antenna_m())


def estimate_series(states: list[ego_pb2.EgoState], lever_arm: LeverArm) -> TrackSeries:
    states = sorted((s for s in states if s.mode != ego_pb2.LOCALISATION_MODE_LOST and s.covariance),
                    key=lambda s: s.header.sample_time_s)
    covariance = np.array([np.asarray(s.covariance).reshape(VEHICLE_STATE_DIM, VEHICLE_STATE_DIM)[
        np.ix_(POSE_ROWS, POSE_ROWS)] for s in states]).reshape(-1, 3, 3)
    return TrackSeries("estimate", np.array([s.header.sample_time_s for s in states]),
                       np.array([s.latitude_deg for s in states]), np.array([s.longitude_deg for s in states]),
                       np.array([s.heading_rad for s in states]), np.array([s.speed_mps for s in states]),
                       covariance, lever_arm)


def fix_series(fixes) -> TrackSeries:
    fixes = sorted(fixes, key=lambda f: f.header.sample_time_s)
    return TrackSeries("fixes", np.array([f.header.sample_time_s for f in fixes]),
                       np.array([f.latitude_deg for f in fixes]), np.array([f.longitude_deg for f in fixes]),
                       compass_to_enu_rad(np.array([f.course_deg for f in fixes])),
                       np.array([f.speed_mps for f in fixes]))


def score_against_reference(request: ReferenceRequest) -> tuple[list[ReferenceScore], LeverArm]:
    """The estimate's score, then the fixes' (when the recording holds them), and the lever arm the estimate was
    moved by. ValueError (ReferenceError, RecordingError among them) says why a recording or reference cannot be
    scored."""
    messages = RunMessages.from_recording(request.recording)
    fixes = messages.gnss_fixes.get(request.vehicle_id, [])
    if request.reference is not None:
        reference = ReferenceTrack.load(request.reference)
    elif fixes:
        standing = fix_series(fixes)
        reference = ReferenceTrack.standing(standing.time_s, standing.lat_deg, standing.lon_deg)
    else:
        raise ValueError(f"{request.recording}: no gnss/fix of vehicle {request.vehicle_id} to take the mean of "
                         f"(--standstill judges against the recording's own fixes)")
    states = messages.ego_states.get(request.vehicle_id, [])
    lever_arm = request.lever_arm or recorded_antenna(request.recording, request.vehicle_id)
    series = estimate_series(states, lever_arm)
    if not len(series.time_s):
        raise ValueError(f"{request.recording}: no ego/state of vehicle {request.vehicle_id} with a position "
                         f"(replay geolocation with --out first)")
    # A reference that stands still is the same at every offset: no time offset to fit.
    max_offset_s = request.max_offset_s if request.reference is not None else 0.0
    scores = [score_series(series, reference, max_offset_s)]
    if fixes:
        scores.append(score_series(fix_series(fixes), reference, max_offset_s))
    return scores, lever_arm


def _cell(value) -> str:
    return "–" if value is None else f"{value:.3f}" if isinstance(value, float) else str(value)


def print_table(request: ReferenceRequest, scores: list[ReferenceScore]) -> None:
    table = Table(title=f"{request.recording} against {request.reference_name}")
    table.add_column("figure", no_wrap=True)
    for score in scores:
        table.add_column(f"{score.name}\nbest fit", justify="right")
        table.add_column(f"{score.name}\nstamped", justify="right")
    table.add_row("time offset (s)", *[cell for s in scores for cell in (f"{s.offset_s:+.3f}", "+0.000")])
    names = list(dict.fromkeys(name for s in scores for name in s.best_fit))
    for name in names:
        table.add_row(name, *[_cell(figures.get(name)) for s in scores for figures in (s.best_fit, s.stamped)])
    Console().print(table)
    print(f"a consistent 2-D estimate holds the reference in its 2-sigma ellipse {CONSISTENT_TWO_SIGMA_SHARE:.1%} "
          f"of the time, with a mean NEES of 2")


def reference_score_command(request: ReferenceRequest) -> int:
    try:
        scores, lever_arm = score_against_reference(request)
    except (ValueError, OSError, McapError, struct.error) as error:  # ReferenceError, RecordingError among them
        print(f"coopdrive: score: {error}", file=sys.stderr)
        return EXIT_USAGE
    figures = {"recording": str(request.recording),
               "reference": STANDING_REFERENCE if request.reference is None else str(request.reference),
               "lever_arm_m": [lever_arm.x_m, lever_arm.y_m],
               "consistent_two_sigma_share": CONSISTENT_TWO_SIGMA_SHARE,
               "scores": [score.as_dict() for score in scores]}
    if request.out is not None:
        request.out.write_text(json.dumps(figures, indent=2))
    if request.as_json:
        print(json.dumps(figures, indent=2))
    else:
        print_table(request, scores)
    if request.report is not None:
        try:
            page = write_reference_report(request.report,
                                          f"{request.recording.name} against {request.reference_name}", scores)
        except OSError as error:
            print(f"coopdrive: score: --report {request.report}: {error.strerror or error}", file=sys.stderr)
            return EXIT_USAGE
        print(f"report: {page}", file=sys.stderr if request.as_json else sys.stdout)
    return EXIT_OK
