"""Vehicle CAN: the DBC, its codec, reading the bus and candump logging.

- `vehicle.dbc`: ACT_ command frames (automation -> vehicle), VEH_ feedback and inertial frames (vehicle ->
  automation), RDR_ radar object list. Frames are named by `frames.VehicleFrame`; ids come from the DBC.
- `codec.VehicleCanCodec`: commands, VehicleCanState, ImuSample and RadarTracks <-> can.Message, with rolling
  counters and checksums; bad frames raise `frames.CanDecodeError` with a `DecodeFailure` reason.
- `adapter.VehicleCanAdapter` (a YAML file beside a car's DBC, `vehicle_adapter.yaml` for the simulator's car):
  where a car's bus carries each quantity; `adapter_decoder.AdapterDecoder` turns its frames into
  VehicleCanState and ImuSample.
- `bus_reader.VehicleBusReader`: the frames one service uses, decoded and handed on; the rest counted.
- `vehicle_port.VehicleCanPort`: a python-can interface (SocketCAN on the vehicle); `bus_input.VehicleBusInput`
  picks it or the can/vehicle topic; `wire`: can.Message <-> coopdrive.v1 CanFrame.
- `candump.CandumpLogger` / `candump.read_candump`: candump .log files through python-can.
"""
