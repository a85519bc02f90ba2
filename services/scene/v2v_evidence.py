"""What tells which track a V2V station is: whether our own sensors fixed a track lately, the free track they see
nearest a station's claim or agreeing with it, and how far the claim is from our fix (the tracker's link_v2v)."""

from __future__ import annotations

from collections.abc import Iterable

import numpy as np

from .config import TrustConfig
from .measurement import Measurement
from .occupancy import nearest_body_point
from .track import Track, TrackStatus


def seen_lately(track: Track, time_s: float, trust: TrustConfig) -> bool:
    """Whether our LiDAR or radar fixed the track within max_sensor_age_s of time_s."""
    fix = track.ranging_fix
    return fix is not None and time_s - fix.time_s <= trust.max_sensor_age_s


def nearest_free_ranging(tracks: Iterable[Track], meas: Measurement, trust: TrustConfig) -> Track | None:
    """The unlinked, confirmed LiDAR/radar track seen lately that is nearest the claim, if within link_gate_m.

    Confirmed only: the station's object is dropped for it, and a tentative track is not published, so a
    car beside us that one radar reading started a track on vanished from the scene until that track was
    confirmed (merge seed 4: for three frames, the very frames a merger checked its side and changed lane)."""
    best, best_gap = None, trust.link_gate_m
    for track in tracks:
        if (track.station_id is None and track.status is TrackStatus.CONFIRMED
                and seen_lately(track, meas.time_s, trust)):
            gap = float(np.linalg.norm(Track.position_of(track.predicted_mean(meas.time_s)) - meas.position_m))
            if gap <= best_gap:
                best, best_gap = track, gap
    return best


def agreeing_free_track(tracks: Iterable[Track], meas: Measurement, trust: TrustConfig) -> Track | None:
    for track in tracks:
        if track.station_id is None:
            disagreement = disagreement_m(track, meas, trust)
            if disagreement is not None and disagreement <= trust.agree_m:
                return track
    return None


def disagreement_m(track: Track, meas: Measurement, trust: TrustConfig) -> float | None:
    """Distance from the V2V claim to our latest LiDAR/radar fix, moved to the claim's time.

    Our fix is the claimed rear bumper centre when our sensors see the car's rear (or its front, which they take
    back to its rear), but the point of its body nearest them when they see its flank or a corner: a radar's
    strongest return. The claim agrees with whichever of the two its own body puts nearer our fix. Measured
    against the rear alone, an honest organiser's car crossing the T-intersection in front of us read 3-4 m
    off, and our trust in it fell from 0.6 to 0 in a second (intersection seed 1)."""
    fix = track.ranging_fix
    if fix is None or abs(meas.time_s - fix.time_s) > trust.max_sensor_age_s:
        return None
    velocity = Track.velocity_of(track.predicted_mean(fix.time_s))
    at_claim = fix.position_m + velocity * (meas.time_s - fix.time_s)
    gap_m = float(np.linalg.norm(meas.position_m - at_claim))
    if None in (meas.heading_rad, meas.length_m, meas.width_m):
        return gap_m
    nearest_m = nearest_body_point(meas.position_m, meas.heading_rad, meas.length_m, meas.width_m, fix.origin_m)
    return min(gap_m, float(np.linalg.norm(nearest_m - at_claim)))
