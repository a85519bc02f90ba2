"""Generated protobuf modules of the coopdrive.v1 message set (see proto/). Do not edit."""
