"""What a replay starts from: the service's config (recorded, a file's, changed by --set) and, when the
recording cannot feed the service, the one line that says which topics it would need."""

from __future__ import annotations

import json
from pathlib import Path

from coopdrive.bus.keys import KeyLayout
from coopdrive.runtime.config import apply_override, read_mapping, validate_config
from coopdrive.runtime.service import Service, ServiceConfig

# The metadata record of a recording that says where each service config came from: "default" for the configs an
# import writes (importer.py), where nothing was recorded; a replay with one of them says so.
CONFIG_SOURCE_METADATA = "coopdrive.config_source"


class ReplayError(RuntimeError):
    pass


def replay_config(cls: type[Service], recording: str | Path, config_key: str, configs: dict[str, str],
                  metadata: dict[str, dict[str, str]], config_file: str | Path | None,
                  overrides: list[str] | tuple[str, ...]) -> tuple[ServiceConfig, list[str]]:
    """The config to replay with and notes for the user: config_file replaces the recorded one, then each
    KEY=VALUE of overrides is applied (as `coopdrive service --set` does)."""
    notes = []
    if config_file is not None:
        data, source = read_mapping(config_file), str(config_file)
    elif config_key in configs:
        data, source = json.loads(configs[config_key]), f"{recording} ({config_key})"
        if metadata.get(CONFIG_SOURCE_METADATA, {}).get(config_key) == "default":
            notes.append(f"{config_key}: the recording holds the service's default config (none was recorded)")
    else:
        recorded = ", ".join(sorted(configs)) or "none"
        raise ReplayError(f"{recording}: no recorded config for {config_key} (recorded: {recorded}); "
                          f"give one with --config FILE")
    for assignment in overrides:
        apply_override(data, assignment)
    if overrides:
        notes.append(f"changed: {', '.join(overrides)}")
    return validate_config(cls.Config, data, source + (" with --set" if overrides else "")), notes


def missing_inputs_text(recording, service_name: str, vehicle_id: str, ctx, recorded_topics: list[str],
                        layout: KeyLayout) -> str:
    wanted = sorted({f"{source}/{topic}"
                     for topic, handlers in ctx.handlers.items() for source, _ in handlers})
    present = {"/".join(parsed) for parsed in map(layout.parse, recorded_topics) if parsed is not None}
    return (f"{recording} holds no input of {service_name} on vehicle {vehicle_id}: missing topics "
            f"{', '.join(wanted) or '(the service subscribes to none)'}; the recording has "
            f"{', '.join(sorted(present)) or 'no messages'}")
