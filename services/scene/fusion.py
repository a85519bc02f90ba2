"""SceneFusion: the scene service's logic, fed by method calls with protobuf values and times.

Every sensor frame is turned into ENU measurements at its own sample time using the ego pose
shifted to that time, associated jointly with the live tracks and fused; V2V observations are first
judged (plausibility, agreement with our own LiDAR/radar, free-space check) and then fused with a
weight that follows the station's trust. `scene(time_s)` predicts every confirmed track to time_s.
Nothing here reads a clock or draws a random number, so the same calls give the same scene.
"""

from __future__ import annotations

import numpy as np

from coopdrive.v1 import ego_pb2, header_pb2, scene_pb2, sensors_pb2

from .config import SceneFusionConfig
from .ego_lane import EgoLaneFusion
from .freespace import FreeSpaceOracle
from .frontends import (
    CameraFrontEnd,
    LaneMarkings,
    RadarFrontEnd,
    RejectCounter,
    SonarFrontEnd,
    V2vFrontEnd,
)
from .lidar import LidarClusterer
from .measurement import EgoPose, Measurement, V2vObservation
from .kalman import IX, IY
from .properties import POSITION
from .scene_builder import FrenetOf, LaneOf, ObjectViews, SceneBuilder
from .track_snapshot import TrackSnapshot
from .tracker import Tracker
from .trust import V2vTrust

LIDAR, RADAR, CAMERA = header_pb2.SENSOR_SOURCE_LIDAR, header_pb2.SENSOR_SOURCE_RADAR, header_pb2.SENSOR_SOURCE_CAMERA
SONAR, V2V = header_pb2.SENSOR_SOURCE_SONAR, header_pb2.SENSOR_SOURCE_V2V


class SceneFusion:
    def __init__(self, config: SceneFusionConfig | None = None, lane_of: LaneOf | None = None,
                 frenet_of: FrenetOf | None = None) -> None:
        """lane_of(x_m, y_m) -> lane index or None, and frenet_of(x_m, y_m) -> (station_m, lateral_m)
        on the current ego lane or None, come from the road map; without them lanes are 4 m bands
        (lidar.lane_margin_m) and gaps run along the ego heading."""
        self.config = config or SceneFusionConfig()
        self.rejects = RejectCounter()
        self._tracker = Tracker(self.config)
        self.trust = V2vTrust(self.config.trust)
        self._lidar = LidarClusterer(self.config.lidar, self.config.ego_length_m - self.config.ego_rear_overhang_m)
        self._radar = RadarFrontEnd(self.config.radar, self.rejects)
        self._camera = CameraFrontEnd(self.config.camera, self.rejects)
        self._sonar = SonarFrontEnd(self.config.sonar, self.rejects)
        self._v2v = V2vFrontEnd(self.config.v2v, self.rejects)
        self._free_space = FreeSpaceOracle(self.config.trust, self.config.radar, self.config.lidar)
        self._builder = SceneBuilder(self.config, lane_of, frenet_of)
        self._ego: EgoPose | None = None
        # The latest ego state itself, for its lane on the map.
        self._ego_state: ego_pb2.EgoState | None = None
        self.lanes = EgoLaneFusion(self.config.lanes)
        self._free_ranges_m: list[float] = []
        self.lane_markings: LaneMarkings | None = None

    # -- inputs ----------------------------------------------------------------------------

    def on_ego(self, ego: ego_pb2.EgoState) -> None:
        try:
            pose = EgoPose.from_state(ego)
        except ValueError as error:
            self.rejects.reject(str(error))
            return
        if self._ego is None or pose.time_s >= self._ego.time_s:
            self._ego, self._ego_state = pose, ego

    def on_lidar(self, scan: sensors_pb2.LidarScan, ego: ego_pb2.EgoState | None = None) -> None:
        pose = self._pose(scan.header.sample_time_s, ego, "lidar")
        if pose is None:
            return
        try:
            measurements = self._lidar.measurements(scan, pose)
        except ValueError as error:
            self.rejects.reject(f"lidar scan: {error}")
            return
        self._free_space.set_lidar(scan, pose)
        self._process(measurements, pose.time_s)

    def on_radar(self, tracks: sensors_pb2.RadarTracks, ego: ego_pb2.EgoState | None = None) -> None:
        pose = self._pose(tracks.header.sample_time_s, ego, "radar")
        if pose is None:
            return
        measurements = self._radar.measurements(tracks, pose)
        self._free_space.set_radar(measurements, pose)
        self._process(measurements, pose.time_s)

    def on_camera(self, frame: sensors_pb2.CameraFrame, ego: ego_pb2.EgoState | None = None) -> None:
        pose = self._pose(frame.header.sample_time_s, ego, "camera")
        if pose is None:
            return
        self.lane_markings = self._camera.lane_markings(frame)
        self._process(self._camera.measurements(frame, pose), pose.time_s)

    def on_sonar(self, ranges: sensors_pb2.SonarRanges, ego: ego_pb2.EgoState | None = None) -> None:
        pose = self._pose(ranges.header.sample_time_s, ego, "sonar")
        if pose is None:
            return
        self._free_ranges_m = self._sonar.free_ranges_m(ranges)
        self._process(self._sonar.measurements(ranges, pose), pose.time_s)

    @property
    def tracker(self) -> Tracker:
        """The tracker, with every V2V reading fused (on_v2v puts off the filter step of most: see Tracker.fuse_v2v)."""
        self._tracker.flush_v2v()
        return self._tracker

    def on_v2v(self, observation: V2vObservation) -> None:
        """One station's reading. Its filter step waits for the next input of another kind or of the same station,
        or for scene(), so that a step's CAMs, one from each station, are filtered in one pass; the result is the
        same as one at a time (tests/scene/test_deferred_v2v.py)."""
        if self._tracker.awaits_v2v(observation.station_id):
            self._tracker.flush_v2v()
        pose = self._pose(observation.sample_time_s, None, "v2v")
        if pose is None:
            return
        meas = self._v2v.measurement(observation, pose)
        if meas is None:
            return
        reason = self.trust.implausibility(observation)
        if reason is not None:
            self.rejects.reject(f"v2v station {observation.station_id}: {reason}")
        link = self._tracker.link_v2v(meas, self.trust.trust(observation.station_id))
        disagreement = link.disagreement_m if link is not None else None
        trust = self.trust.observe(observation, disagreement, plausible=reason is None)
        track = self._tracker.tracks.get(link.track_id) if link is not None else None
        seen_by_us = track is not None and self._tracker.has_ranging(track, meas.time_s)
        if not seen_by_us and self._free_space.is_free(meas.position_m, meas.time_s):
            self.trust.free_space_contradiction(observation.station_id)
            trust = self.trust.trust(observation.station_id)
        if track is None or not seen_by_us:
            # Nothing of ours sees it: V2V is its only source, so it follows the station, and
            # trust decides whether it may be an obstacle (see _views).
            self._tracker.fuse_v2v(meas, link, trust, fuse_kinematics=True, scale_covariance=False,
                                   defer=True)
            return
        agrees = disagreement is None or disagreement <= self.config.trust.agree_m
        fuse = reason is None and agrees and self.trust.trusted(observation.station_id)
        self._tracker.fuse_v2v(meas, link, trust, fuse_kinematics=fuse, defer=True)

    # -- output ----------------------------------------------------------------------------

    def scene(self, time_s: float) -> scene_pb2.Scene:
        self.tracker.expire(time_s)
        ego = self._ego.at(time_s) if self._ego is not None else EgoPose.from_state(ego_pb2.EgoState())
        tracks = sorted(self.tracker.confirmed(), key=lambda t: t.track_id)
        snapshot = TrackSnapshot.take(tracks, self.tracker.properties, time_s, self.config.tracking.jerk_psd_m2ps5)
        scene = self._builder.build(time_s, ego, self._views(snapshot, time_s), list(self._free_ranges_m))
        for station_id, state in sorted(self.trust.stations().items()):
            scene.station_trust.add(station_id=station_id, trust=state.trust, trusted=self.trust.trusted(station_id),
                                    security_failing=state.security_failing, untrusted_signer=state.untrusted_signer)
        scene.ego_lane.CopyFrom(self.lanes.ego_lane(self._ego_state, self.lane_markings, time_s))
        return scene

    def _views(self, snapshot: TrackSnapshot, time_s: float) -> ObjectViews:
        seen_by_us = snapshot.has_source(POSITION, LIDAR) | snapshot.has_source(POSITION, RADAR)
        # Chalmers 4.3.1: sonars only tell that something is at our side, not where; such an
        # object is reported (and narrows free space) but is no MIO or lane neighbour. A camera
        # alone gives a bearing but a poor range: its object, often a car our radar already holds
        # a few metres off, must not take the MIO from that car and brake us for a phantom.
        poorly_placed = snapshot.only_source(POSITION, SONAR) | snapshot.only_source(POSITION, CAMERA)
        # Radar clutter, or readings of a car split off into a track beside it: no MIO to brake for.
        seen_through = self._lidar_sees_through(snapshot, time_s)
        # A radar false alarm is one reading, and noisy camera bearings of a car beside it can confirm its
        # track: an object whose only ranging is one LiDAR or radar reading is no obstacle until another comes.
        lone_ranging = np.array([track.ranging_hits == 1 for track in snapshot.tracks], dtype=bool)
        v2v_only = snapshot.only_source(POSITION, V2V).tolist()
        stations = [track.station_id for track in snapshot.tracks]
        ghost = np.array([station is not None and self.trust.is_ghost(station) for station in stations], dtype=bool)
        ghost &= ~seen_by_us
        # Nothing of ours sees a V2V-only object: the station's trust decides whether it may be an obstacle.
        trusted_v2v = np.array([only and station is not None and self.trust.trusted(station)
                                for only, station in zip(v2v_only, stations, strict=True)], dtype=bool)
        not_an_obstacle = poorly_placed | seen_through | ghost | lone_ranging
        eligible = np.where(np.array(v2v_only, dtype=bool), trusted_v2v, ~not_an_obstacle)
        return ObjectViews(snapshot, eligible, ghost, [self.trust.trust(station) for station in stations])

    def _lidar_sees_through(self, snapshot: TrackSnapshot, time_s: float) -> np.ndarray:
        """Per track: near enough for the LiDAR to see it, not seen by it, and its beams reach past where it would be."""
        through = np.zeros(len(snapshot.tracks), dtype=bool)
        if self._ego is None or not snapshot.tracks:
            return through
        position_m = snapshot.mean[:, [IX, IY]]
        ego = self._ego.at(time_s)
        near = ~snapshot.has_source(POSITION, LIDAR) & (
            np.hypot(*(position_m - ego.position_m).T) <= self.config.trust.lidar_veto_range_m)
        for k in np.flatnonzero(near):
            through[k] = self._free_space.lidar_free(position_m[k], time_s) is True
        return through

    def counters(self) -> dict[str, int]:
        """Diagnostics: tracker events and rejected inputs by reason."""
        out = {f"tracker_{k}": v for k, v in vars(self.tracker.counters).items() if isinstance(v, int)}
        out.update({f"rejected: {k}": v for k, v in self.rejects.counts.items()})
        out["lane_map_camera_disagreements"] = self.lanes.disagreements
        return out

    # -- helpers ---------------------------------------------------------------------------

    def _pose(self, time_s: float, ego: ego_pb2.EgoState | None, what: str) -> EgoPose | None:
        if ego is not None:
            try:
                given = EgoPose.from_state(ego)
            except ValueError as error:
                self.rejects.reject(f"{what}: {error}")
                return None
            if self._ego is None or given.time_s >= self._ego.time_s:
                self._ego, self._ego_state = given, ego
            return given.at(time_s)
        if self._ego is None:
            self.rejects.reject(f"{what}: no ego state yet")
            return None
        return self._ego.at(time_s)

    def _process(self, measurements: list[Measurement], time_s: float) -> None:
        self.tracker.process(measurements)
        self.tracker.expire(time_s)
        self.tracker.merge_duplicates(time_s)
