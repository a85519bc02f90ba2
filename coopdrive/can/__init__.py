"""Vehicle CAN: the DBC, its codec and candump logging (pure logic, no transport).

- `vehicle.dbc`: ACT_ command frames (automation -> vehicle), VEH_ feedback frames (vehicle -> automation),
  RDR_ radar object list. Frames are named by `frames.VehicleFrame`; ids come from the DBC.
- `codec.VehicleCanCodec`: commands, VehicleCanState and RadarTracks <-> can.Message, with rolling counters
  and checksums; bad frames raise `frames.CanDecodeError` with a `DecodeFailure` reason.
- `candump.CandumpLogger` / `candump.read_candump`: candump .log files through python-can.
"""
