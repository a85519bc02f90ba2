"""The package's layers, lowest first: a module imports its own layer and those below it, never one above.

docs/architecture.md draws them (coopdrive.bus.architecture) and tests/test_import_direction.py holds every module to
them, following imports transitively. A new top-level package takes its place here, or that test fails. No imports:
the layers are named, not loaded."""

from __future__ import annotations

from dataclasses import dataclass


@dataclass(frozen=True)
class Layer:
    name: str
    packages: tuple[str, ...]
    holds: str
    framework: bool = True


LAYERS = (
    Layer("messages", ("coopdrive.v1", "coopdrive.messages", "coopdrive.reasons", "coopdrive.exit_status",
                       "coopdrive.geodesy", "coopdrive.vehicle"),
          "the generated protobuf messages and what their values mean; reasons, exit statuses, geodesy; the "
          "vehicles' one description and the spacing policy"),
    Layer("bus and shared formats", ("coopdrive.bus", "coopdrive.gnss", "coopdrive.roadmap"),
          "Zenoh sessions, keys, topics, the services table, the publish spool; NMEA decoding; the lane map"),
    Layer("service runtime", ("coopdrive.runtime",),
          "running a service: its context, life cycle, clock following, the clock master, lockstep steps"),
    Layer("CAN and drawing", ("coopdrive.can", "coopdrive.visual"),
          "the car's CAN bus through python-can; the channels Foxglove draws from the messages"),
    Layer("recordings", ("coopdrive.recording",),
          "writing, reading, replaying, importing and exporting MCAP recordings; the live Foxglove bridge"),
    Layer("V2X library", ("coopdrive.v2x",),
          "GeoNetworking, BTP, ITS PDUs, their mapping, TS 103 097 security and PKI, ITS time, CAM generation"),
    Layer("services", ("coopdrive.services",),
          "the services, each in services/<name> (installed as coopdrive.services.<name>)", framework=False),
    Layer("applications", ("coopdrive.launch", "coopdrive.judging", "coopdrive.analysis", "coopdrive.cli",
                           "coopdrive.cli_baseline", "coopdrive.cli_deploy", "coopdrive.cli_judging",
                           "coopdrive.cli_recording", "coopdrive.cli_service", "coopdrive.docs_reference"),
          "starting runs, batches and sweeps; judging them; the command line and its generated reference",
          framework=False),
)
# The package's own __init__ (which sets the environment up before numpy loads) stands below every layer.
ROOT_PACKAGE = "coopdrive"


def layer_of(module: str) -> Layer | None:
    for layer in LAYERS:
        if any(module == package or module.startswith(package + ".") for package in layer.packages):
            return layer
    return None
