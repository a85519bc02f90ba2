"""GNSS receiver input as a library: NMEA 0183 sentences decoded into GnssFix messages, for the geolocation service
and every reader of a recording's raw receiver bytes (the Foxglove channels)."""
