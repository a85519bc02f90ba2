"""Multi-object tracker: gating, global assignment, track life cycle, V2V station links.

Life cycle: a track starts tentative and is never published; it is confirmed after confirm_hits
readings; a tentative track with no hit for
tentative_timeout_s is deleted, a confirmed one once every source of its position has faded.
A false detection therefore never shows, and a false object never outlives its last reading by more
than the longest fade time of the sources that saw it.
"""

from __future__ import annotations

from dataclasses import dataclass, field, replace

import numpy as np
from scipy.spatial import cKDTree

from coopdrive.v1 import header_pb2

from .association import match_quality
from .config import SceneFusionConfig
from .frame_association import associate_confirmed_first
from .frame_geometry import FrameGeometry
from .measurement import Measurement
from .properties import POSITION, ObjectProperties, property_table, support_many
from .track import RANGING_SOURCES, Track, TrackStatus, filter_steps, predict_positions
from .v2v_evidence import agreeing_free_track, disagreement_m, nearest_free_ranging, seen_lately


_SONAR = header_pb2.SENSOR_SOURCE_SONAR
# Trust below which a station's covariance stops growing as 1/trust^2 (a finite number, however little it counts).
MIN_TRUST = 1e-3


def station_variance_scale(trust: float) -> float:
    """Less trusted stations count for less: what their variances are multiplied by, 1/trust^2."""
    return 1.0 / max(trust, MIN_TRUST) ** 2


def _moved(meas: Measurement, offset_m: np.ndarray) -> Measurement:
    """meas with its position moved by offset_m (2,)."""
    return replace(meas, position_m=meas.position_m + offset_m)


@dataclass
class TrackerCounters:
    created: int = 0
    confirmed: int = 0
    deleted: int = 0
    too_late: int = 0
    replayed: int = 0
    v2v_not_fused: int = 0
    # Readings matching no track that were too ambiguous to start one (see Measurement.ambiguous).
    ambiguous_unmatched: int = 0
    # Confirmed tracks found to be one vehicle and made one (see Tracker.merge_duplicates).
    duplicates_merged: int = 0
    # Readings matching no track that lay inside a confirmed vehicle's body (see occupancy.py).
    inside_known_vehicle: int = 0
    # Sonar echoes matched to an object another sensor holds, which they do not move (see Tracker.process).
    echoes_on_objects_others_hold: int = 0
    by_reason: dict[str, int] = field(default_factory=dict)


@dataclass(frozen=True, slots=True)
class _DeferredV2v:
    """A V2V reading in sequence on its track, waiting for Tracker.flush_v2v, and the weight of its support."""

    track: Track
    measurement: Measurement
    weight: float


@dataclass(frozen=True)
class V2vLink:
    """Where a V2V measurement went and how far it was from our own ranging fix."""

    track_id: int
    disagreement_m: float | None


class Tracker:
    def __init__(self, config: SceneFusionConfig) -> None:
        self._config = config
        self.tracks: dict[int, Track] = {}
        self._next_id = 1
        self._station_links: dict[int, int] = {}
        self.counters = TrackerCounters()
        # Looked up for every property of every object on every update: resolve the table once.
        sources = (header_pb2.SENSOR_SOURCE_LIDAR, header_pb2.SENSOR_SOURCE_RADAR, header_pb2.SENSOR_SOURCE_CAMERA,
                   header_pb2.SENSOR_SOURCE_SONAR, header_pb2.SENSOR_SOURCE_V2V)
        self._source_configs = {source: config.source(source) for source in sources}
        # Every track's properties, one row each.
        self.properties = property_table(self._source_configs.__getitem__, config.tracking)
        self._frames = FrameGeometry(config, self.properties)
        # V2V readings fuse_v2v(defer=True) has put off, in order: each in sequence on a track of its own.
        self._deferred_v2v: list[_DeferredV2v] = []

    # -- sensor frames ---------------------------------------------------------------------

    def process(self, measurements: list[Measurement]) -> None:
        """One frame of one sensor: associate jointly, confirmed tracks first, update, start tentative tracks for
        the rest."""
        self.flush_v2v()
        if not measurements:
            return
        tracks = list(self.tracks.values())
        gate = self._config.tracking.gate_chi2
        prior = self._frames.prior(tracks, measurements[0].time_s) if tracks else None
        front_m = self._frames.front_faces(tracks, prior, measurements[0].origin_m)
        confirmed = np.fromiter((t.status is TrackStatus.CONFIRMED for t in tracks), dtype=bool, count=len(tracks))
        fused, unmatched = associate_confirmed_first(*self._frames.geometry(measurements, tracks, prior, front_m), confirmed,
                                                     self._config.tracking,
                                                     self._frames.range_rate_terms_of(measurements, prior))
        # In measurement order, as one joint assignment would fuse and start them; each reading of a face taken
        # back to the rear its track holds.
        facing = front_m.any(axis=1)
        pairs = [(tracks[j], _moved(measurements[i], -front_m[j]) if facing[j] else measurements[i],
                  match_quality(cost, gate)) for i, j, cost in sorted(fused)]
        self._fuse_frame(self._without_echoes_on_objects_others_hold(pairs))
        starting = [measurements[i] for i in sorted(unmatched) if not measurements[i].ambiguous]
        self.counters.ambiguous_unmatched += len(unmatched) - len(starting)
        if starting:
            inside = self._frames.inside_vehicles(self.confirmed(), starting)
            self.counters.inside_known_vehicle += int(inside.sum())
            starting = [meas for meas, occupied in zip(starting, inside, strict=True) if not occupied]
        if starting:
            started = [self._new_track(meas) for meas in starting]
            support_many([track.props for track in started], starting, np.ones(len(starting)))
            for track in started:
                self._maybe_confirm(track)

    def _without_echoes_on_objects_others_hold(self, pairs: list[tuple[Track, Measurement, float]]) -> list:
        """The pairs to fuse: a sonar echo moves only an object the sonars alone hold.

        Chalmers 4.3.1: a sonar tells that something is at our side, not where. Its echo comes from the surface
        nearest it, anywhere in its cone: from a car beside us, the near side of its flank, half a width short of
        its centre line and at whatever point of its length passes the sonar. Fused into a car our LiDAR, radar or
        camera holds, echoes pinned beside us as a car slid past made it drive along with us and into our lane
        (a car passing the other way at the T-intersection; a radar false alarm they confirmed as a car crossing
        our path). Such an echo is still that object's, so it starts none of its own."""
        kept = [pair for pair in pairs if pair[1].source != _SONAR
                or set(pair[0].props.position.sources(pair[1].time_s)) <= {_SONAR}]
        self.counters.echoes_on_objects_others_hold += len(pairs) - len(kept)
        return kept

    # -- V2V -------------------------------------------------------------------------------

    def link_v2v(self, meas: Measurement, trust: float = 1.0) -> V2vLink | None:
        """The track this station (of this trust so far) is or becomes linked to, without fusing the reading yet."""
        station = meas.station_id
        linked = self._station_links.get(station)
        if linked is not None and linked in self.tracks:
            if not seen_lately(self.tracks[linked], meas.time_s, self._config.trust):
                # Our sensors now see a car near where this object only V2V keeps up is: that is the
                # same vehicle, so the V2V-only duplicate goes and the station moves to the seen track,
                # with the motion the station gave it (emergency seed 6: a track begun at 2.1 m/s on an
                # ambulance passing at 25 lost its readings, drifted on beside us and was braked for).
                seen = nearest_free_ranging(self.tracks.values(), meas, self._config.trust)
                if seen is not None:
                    seen.take_motion(self.tracks[linked], station_variance_scale(trust))
                    self._remove(linked)
                    return self._link(seen, meas)
            link = V2vLink(linked, disagreement_m(self.tracks[linked], meas, self._config.trust))
            if link.disagreement_m is None or link.disagreement_m <= self._config.trust.agree_m:
                return link
            # The link itself may be the mistake (two cars close together): move it to a track our
            # own sensors see where the station says it is, if there is one; otherwise keep it.
            better = agreeing_free_track(self.tracks.values(), meas, self._config.trust)
            if better is None:
                return link
            self.tracks[linked].station_id = None
            return self._link(better, meas)
        free = [t for t in self.tracks.values() if t.station_id is None]
        if free:
            cost = self._frames.costs([meas], free)[0][0]
            best = int(np.argmin(cost))
            if cost[best] <= self._config.tracking.gate_chi2:
                return self._link(free[best], meas)
            # An offset station lands outside the gate; a ranging track within a car length still
            # takes it, so the offset shows up as disagreement rather than as a second object.
            seen = nearest_free_ranging(self.tracks.values(), meas, self._config.trust)
            if seen is not None:
                return self._link(seen, meas)
        return None

    def _link(self, track: Track, meas: Measurement) -> V2vLink:
        track.station_id = meas.station_id
        self._station_links[meas.station_id] = track.track_id
        return V2vLink(track.track_id, disagreement_m(track, meas, self._config.trust))

    def fuse_v2v(self, meas: Measurement, link: V2vLink | None, trust: float, fuse_kinematics: bool,
                 scale_covariance: bool = True, defer: bool = False) -> int:
        """Fuse a V2V measurement into its linked track (or a new one); returns the track id.

        scale_covariance=False for objects only V2V sees: there the station is the only source of the
        position, and its trust shows in confidence, v2v_trust and eligibility instead.

        defer=True: a reading in sequence on its track waits for flush_v2v, which filters every waiting track in
        one pass (a step brings a CAM of each station in a row). The caller flushes before the next reading of the
        same station (awaits_v2v); link_v2v reads no other station's track, only the station's own and tracks no
        station holds. process, expire, merge_duplicates, confirmed and track_of_station flush first."""
        if link is None:
            track = self._start(meas, max(trust, self._config.trust.min_support_weight))
            self._link(track, meas)
            return track.track_id
        track = self.tracks[link.track_id]
        weight = max(trust, self._config.trust.min_support_weight)
        if fuse_kinematics:
            scale = station_variance_scale(trust) if scale_covariance else 1.0
            scaled = replace(meas, cov_m2=meas.cov_m2 * scale, velocity_std_mps=meas.velocity_std_mps * scale**0.5)
            if defer and scaled.time_s >= track.time_s:
                self._deferred_v2v.append(_DeferredV2v(track, scaled, weight))
            else:
                self._fuse(track, scaled, 1.0, v2v_weight=weight)
        else:
            self.counters.v2v_not_fused += 1
            track.props.station_id.update(meas.source, meas.time_s, float(meas.station_id), weight)
        return track.track_id

    def awaits_v2v(self, station_id: int | None) -> bool:
        """Whether a reading of this station waits for flush_v2v."""
        return any(deferred.measurement.station_id == station_id for deferred in self._deferred_v2v)

    def flush_v2v(self) -> None:
        """Fuse the readings fuse_v2v(defer=True) put off: what _fuse does for each, their filter steps in one pass
        (filter_steps gives each row the bits its track's own step would)."""
        if not self._deferred_v2v:
            return
        deferred, self._deferred_v2v = self._deferred_v2v, []
        x, p = filter_steps([item.track for item in deferred], [item.measurement for item in deferred],
                            self._config.tracking)
        for item, x_k, p_k in zip(deferred, x, p, strict=True):
            item.track.accept(item.measurement, x_k, p_k)
            if not item.measurement.ambiguous:
                item.track.props.support(item.measurement, 1.0, item.weight)
            self._maybe_confirm(item.track)

    # -- life cycle ------------------------------------------------------------------------

    def _fuse_frame(self, pairs: list[tuple[Track, Measurement, float]]) -> None:
        """Fuse one frame's (track, measurement, match quality) pairs, each track at most once: the in-sequence
        ones through one batched filter step, the late ones by their tracks' replay."""
        in_sequence = [pair for pair in pairs if pair[1].time_s >= pair[0].time_s]
        late = [pair for pair in pairs if pair[1].time_s < pair[0].time_s]
        if in_sequence:
            x, p = filter_steps([track for track, _, _ in in_sequence], [meas for _, meas, _ in in_sequence],
                                self._config.tracking)
            for (track, meas, _), x_k, p_k in zip(in_sequence, x, p, strict=True):
                track.accept(meas, x_k, p_k)
            credited = [pair for pair in in_sequence if not pair[1].ambiguous]
            if credited:
                support_many([track.props for track, _, _ in credited], [meas for _, meas, _ in credited],
                             [quality for _, _, quality in credited])
            for track, _, _ in in_sequence:
                self._maybe_confirm(track)
        for track, meas, quality in late:
            self._fuse(track, meas, quality)

    def _fuse(self, track: Track, meas: Measurement, quality: float, v2v_weight: float = 1.0) -> None:
        replays_before = track.replays
        if not track.apply(meas):
            self.counters.too_late += 1
            return
        self.counters.replayed += track.replays - replays_before
        if not meas.ambiguous:
            track.props.support(meas, quality, v2v_weight)
        self._maybe_confirm(track)

    def _start(self, meas: Measurement, v2v_weight: float = 1.0) -> Track:
        track = self._new_track(meas)
        track.props.support(meas, 1.0, v2v_weight)
        self._maybe_confirm(track)
        return track

    def _new_track(self, meas: Measurement) -> Track:
        """A tentative track whose prior is meas; its properties not yet credited with it."""
        props = ObjectProperties(self._source_configs.__getitem__, self._config.tracking, self.properties)
        track = Track(self._next_id, meas, self._config.tracking, props)
        self._next_id += 1
        self.tracks[track.track_id] = track
        self.counters.created += 1
        return track

    def _maybe_confirm(self, track: Track) -> None:
        if track.status is not TrackStatus.TENTATIVE:
            return
        # Hits only: a clutter point and a radar false alarm that happen to coincide are two sources.
        if track.hits >= self._config.tracking.confirm_hits:
            track.status = TrackStatus.CONFIRMED
            self.counters.confirmed += 1

    def expire(self, time_s: float) -> None:
        """Delete tentative tracks that went quiet and confirmed ones whose position faded."""
        self.flush_v2v()
        timeout = self._config.tracking.tentative_timeout_s
        dead = [t.track_id for t in self.tracks.values()
                if t.status is TrackStatus.TENTATIVE and time_s - t.last_hit_s > timeout]
        confirmed = self.confirmed()
        if confirmed:
            faded = self.properties.faded([t.props.row for t in confirmed], POSITION, time_s)
            dead += [t.track_id for t, gone in zip(confirmed, faded, strict=True) if gone]
        for track_id in dead:
            self._remove(track_id)

    def merge_duplicates(self, time_s: float) -> None:
        """Confirmed tracks closer than two vehicles can be and moving alike are one vehicle whose readings
        split between them (a radar sees a car's near corner, a LiDAR its rear face): the older track, whose
        id others already know, stays; the younger goes, and its station link moves to the older one. Two
        tracks of different stations are never merged."""
        cfg = self._config.tracking
        tracks = sorted(self.confirmed(), key=lambda t: t.track_id)
        if len(tracks) < 2:
            return
        positions_m, _ = predict_positions(tracks, time_s, cfg.jerk_psd_m2ps5)
        # kd-tree pairs: the cost grows as n log n with the number of objects, not n^2.
        for older_index, younger_index in sorted(cKDTree(positions_m).query_pairs(cfg.duplicate_distance_m)):
            older, younger = tracks[older_index], tracks[younger_index]
            if older.track_id not in self.tracks or younger.track_id not in self.tracks:
                continue
            if None not in (older.station_id, younger.station_id) and older.station_id != younger.station_id:
                continue
            speed_difference_mps = np.linalg.norm(Track.velocity_of(older.mean) - Track.velocity_of(younger.mean))
            if speed_difference_mps > cfg.duplicate_speed_difference_mps:
                continue
            station = younger.station_id
            self._remove(younger.track_id)
            self.counters.duplicates_merged += 1
            if station is not None and older.station_id is None:
                older.station_id = station
                self._station_links[station] = older.track_id

    def _remove(self, track_id: int) -> None:
        track = self.tracks.pop(track_id)
        track.status = TrackStatus.DELETED
        track.props.release()
        if track.station_id is not None and self._station_links.get(track.station_id) == track_id:
            del self._station_links[track.station_id]
        self.counters.deleted += 1

    def confirmed(self) -> list[Track]:
        self.flush_v2v()
        return [t for t in self.tracks.values() if t.status is TrackStatus.CONFIRMED]

    def track_of_station(self, station_id: int) -> Track | None:
        self.flush_v2v()
        track_id = self._station_links.get(station_id)
        return self.tracks.get(track_id) if track_id is not None else None

    @staticmethod
    def has_ranging(track: Track, time_s: float) -> bool:
        return any(track.props.position.has_source(s, time_s) for s in RANGING_SOURCES)

