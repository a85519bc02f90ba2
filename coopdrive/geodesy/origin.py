"""The WGS84 origin of the local ENU frame: one setting, the same in every service that needs one."""

from __future__ import annotations

from pydantic import BaseModel, ConfigDict, Field


class GeodeticOrigin(BaseModel):
    """WGS84 origin of the local ENU frame; by default the GCDC 2016 site on the A270 near Helmond."""

    model_config = ConfigDict(extra="forbid", frozen=True)

    lat_deg: float = Field(51.4758, ge=-90.0, le=90.0)
    lon_deg: float = Field(5.6247, ge=-180.0, le=180.0)
    alt_m: float = 20.0

    def as_tuple(self) -> tuple[float, float, float]:
        return self.lat_deg, self.lon_deg, self.alt_m
