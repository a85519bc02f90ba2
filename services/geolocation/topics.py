"""The topics geolocation publishes and reads (read by the framework's topic registry: imports only messages)."""

from coopdrive.bus.topic import Topic
from coopdrive.v1 import ego_pb2, gnss_pb2

PUBLISHER = "geolocation"

PUBLISHES = (
    Topic("ego/state", ego_pb2.EgoState, PUBLISHER),
    Topic("ego/gnss", gnss_pb2.GnssFix, PUBLISHER),
    # What the receiver's port delivered, stamped on arrival: geolocation's estimator reads this stream.
    Topic("gnss/nmea", gnss_pb2.NmeaChunk, PUBLISHER),
)

# Which GNSS input it reads depends on the config and on replay (services/geolocation/service.py: gnss_sources);
# gnss/serial_mark only when a lockstep run paces its serial port by the simulator's marks.
SUBSCRIBES = ("can/vehicle", "gnss/fix", "gnss/nmea", "gnss/serial_mark")
