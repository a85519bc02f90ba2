"""MCAP recording of bus traffic with protobuf schemas (Foxglove opens the files), and replay."""
