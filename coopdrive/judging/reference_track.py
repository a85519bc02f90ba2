"""ReferenceTrack: a reference trajectory from a CSV file (time, lat, lon[, heading, speed]), as a team gets one from
a better system (an INS/GNSS post-processing, a survey-grade receiver), to judge an estimate with.

Columns, by name (the first row): `time` (Unix seconds, the recording's time base), `lat` / `latitude_deg`,
`lon` / `longitude_deg`, optionally `heading` / `heading_deg` (degrees clockwise from north) and `speed` /
`speed_mps`. Other columns are ignored. Positions are put on a local tangent plane at the first row.
"""

from __future__ import annotations

import csv
from pathlib import Path

import numpy as np

from coopdrive.geodesy import LocalTangentPlane

COLUMN_NAMES = {
    "time": ("time", "time_s", "t_s"),
    "lat": ("lat", "latitude", "latitude_deg", "lat_deg"),
    "lon": ("lon", "longitude", "longitude_deg", "lon_deg"),
    "heading": ("heading", "heading_deg"),
    "speed": ("speed", "speed_mps"),
}
REQUIRED = ("time", "lat", "lon")
MIN_ROWS = 2


class ReferenceError(ValueError):
    """A reference file that cannot be used; str() names the file and what is wrong."""


def compass_to_enu_rad(heading_deg: np.ndarray) -> np.ndarray:
    """Degrees clockwise from north to the ENU heading (radians counter-clockwise from east)."""
    return np.pi / 2.0 - np.radians(heading_deg)


def wrap_rad(angle_rad: np.ndarray) -> np.ndarray:
    return (angle_rad + np.pi) % (2.0 * np.pi) - np.pi


class ReferenceTrack:
    def __init__(self, time_s: np.ndarray, lat_deg: np.ndarray, lon_deg: np.ndarray,
                 heading_deg: np.ndarray | None = None, speed_mps: np.ndarray | None = None) -> None:
        self.time_s = time_s
        self.plane = LocalTangentPlane(float(lat_deg[0]), float(lon_deg[0]))
        enu = [self.plane.to_enu(float(lat), float(lon)) for lat, lon in zip(lat_deg, lon_deg)]
        self.east_m = np.array([e for e, _, _ in enu])
        self.north_m = np.array([n for _, n, _ in enu])
        if heading_deg is None:  # the track's own direction
            heading_rad = np.arctan2(np.gradient(self.north_m, time_s), np.gradient(self.east_m, time_s))
        else:
            heading_rad = compass_to_enu_rad(heading_deg)
        self.heading_rad = np.unwrap(heading_rad)  # interpolated without a jump at +-180 deg
        self.has_heading = heading_deg is not None
        self.speed_mps = speed_mps

    @classmethod
    def load(cls, path: str | Path) -> ReferenceTrack:
        path = Path(path)
        try:
            with open(path, newline="") as stream:
                rows = list(csv.reader(stream))
        except (OSError, UnicodeDecodeError) as error:
            raise ReferenceError(f"{path}: not a readable CSV file ({error})") from None
        if not rows:
            raise ReferenceError(f"{path}: empty; expected a header row with time, lat, lon[, heading, speed]")
        header = [name.strip().lower() for name in rows[0]]
        columns = {key: next((header.index(n) for n in names if n in header), None)
                   for key, names in COLUMN_NAMES.items()}
        missing = [key for key in REQUIRED if columns[key] is None]
        if missing:
            raise ReferenceError(f"{path}: no column {', '.join(missing)} (columns: {', '.join(header)}); expected "
                                 f"time, lat, lon[, heading, speed]")
        values = {key: cls._column(path, rows[1:], index, key) for key, index in columns.items() if index is not None}
        if len(values["time"]) < MIN_ROWS or np.any(np.diff(values["time"]) <= 0.0):
            raise ReferenceError(f"{path}: needs at least {MIN_ROWS} rows with times increasing")
        return cls(values["time"], values["lat"], values["lon"], values.get("heading"), values.get("speed"))

    @classmethod
    def standing(cls, time_s: np.ndarray, lat_deg: np.ndarray, lon_deg: np.ndarray) -> ReferenceTrack:
        """A receiver that stood still: the mean of its fixes, over their times. It is not the truth: it holds what
        the fixes share (a slow bias), so an estimate judged against it is judged on its scatter, a lower bound of
        its error. With no direction of travel, along-track is east and across-track north."""
        if len(time_s) < MIN_ROWS or np.any(np.diff(time_s) <= 0.0):
            raise ReferenceError(f"a standing reference needs at least {MIN_ROWS} fixes with times increasing")
        plane = LocalTangentPlane(float(lat_deg[0]), float(lon_deg[0]))
        enu = np.array([plane.to_enu(float(lat), float(lon))[:2] for lat, lon in zip(lat_deg, lon_deg)])
        mean_lat, mean_lon, _ = plane.to_geodetic(*enu.mean(axis=0))
        count = len(time_s)
        return cls(np.asarray(time_s, float), np.full(count, mean_lat), np.full(count, mean_lon),
                   speed_mps=np.zeros(count))

    @staticmethod
    def _column(path: Path, rows: list[list[str]], index: int, key: str) -> np.ndarray:
        try:
            column = np.array([float(row[index]) for row in rows if row])
        except (ValueError, IndexError):
            raise ReferenceError(f"{path}: column {key}: a row without a number there") from None
        if not np.all(np.isfinite(column)):
            raise ReferenceError(f"{path}: column {key}: not every value is finite")
        return column

    def span_s(self) -> tuple[float, float]:
        return float(self.time_s[0]), float(self.time_s[-1])

    def at(self, time_s: np.ndarray) -> dict[str, np.ndarray]:
        """east_m, north_m, heading_rad (and speed_mps when given) interpolated at these times (inside the span)."""
        out = {"east_m": np.interp(time_s, self.time_s, self.east_m),
               "north_m": np.interp(time_s, self.time_s, self.north_m),
               "heading_rad": wrap_rad(np.interp(time_s, self.time_s, self.heading_rad))}
        if self.speed_mps is not None:
            out["speed_mps"] = np.interp(time_s, self.time_s, self.speed_mps)
        return out

