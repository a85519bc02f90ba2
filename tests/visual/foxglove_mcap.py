"""Reading the Foxglove channels of a recording back with Foxglove's own protobuf classes."""

from collections import defaultdict
from pathlib import Path

from foxglove_schemas_protobuf.FrameTransforms_pb2 import FrameTransforms
from foxglove_schemas_protobuf.GeoJSON_pb2 import GeoJSON
from foxglove_schemas_protobuf.LocationFix_pb2 import LocationFix
from foxglove_schemas_protobuf.SceneUpdate_pb2 import SceneUpdate
from google.protobuf.descriptor_pb2 import FileDescriptorSet
from mcap.reader import make_reader

FOXGLOVE_CLASSES = {cls.DESCRIPTOR.full_name: cls for cls in (LocationFix, FrameTransforms, SceneUpdate, GeoJSON)}


def foxglove_channels(path: Path) -> dict[str, list]:
    """topic -> its messages decoded by the foxglove-schemas-protobuf class its schema names, in log order;
    asserts each schema is that class's own file descriptor."""
    decoded: dict[str, list] = defaultdict(list)
    with open(path, "rb") as stream:
        for schema, channel, message in make_reader(stream).iter_messages(log_time_order=True):
            if not schema.name.startswith("foxglove."):
                continue
            cls = FOXGLOVE_CLASSES[schema.name]
            files = {f.name: f for f in FileDescriptorSet.FromString(schema.data).file}
            assert files[cls.DESCRIPTOR.file.name].SerializeToString() == \
                cls.DESCRIPTOR.file.serialized_pb, f"{schema.name}: not Foxglove's published schema"
            decoded[channel.topic].append(cls.FromString(message.data))
    return decoded
