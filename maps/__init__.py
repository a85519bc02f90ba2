"""Road maps shipped with coopdrive (GeoJSON, WGS84)."""
