"""What Foxglove draws of a drive: channels derived from the stack's messages (see channels.py)."""

from coopdrive.visual.channels import VisualChannels, recorded_road_map

__all__ = ["VisualChannels", "recorded_road_map"]
