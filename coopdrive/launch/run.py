"""Runs a scenario: a hub session, an optional recorder, the simulator and every stack's services."""

from __future__ import annotations

import json
import math
import shutil
import signal
import tempfile
import threading
import time
from dataclasses import dataclass
from pathlib import Path
from typing import TYPE_CHECKING, Any, Callable

from google.protobuf.message import Message
from pydantic import ConfigDict

from coopdrive.bus import Bus, BusConfig
from coopdrive.bus.keys import WORLD_ID
from coopdrive.launch.lockstep_give_ups import DIAGNOSTICS_KEYS, LockstepGiveUps
from coopdrive.launch.ports import free_tcp_port, free_udp_ports, loopback_endpoint
from coopdrive.launch.process_layout import ProcessLayout
from coopdrive.launch.processes import ServiceProcesses, ServiceSpec
from coopdrive.launch.run_aborted import RunAborted
from coopdrive.launch.run_spec import RunSpec, merged
from coopdrive.launch.scenario_source import ScenarioSource, resolve_scenario
from coopdrive.launch.stack_config import vehicle_overrides
from coopdrive.recording.spool_merge import SpoolMerge, spool_paths
from coopdrive.runtime.barrier import MESSAGES_GIVEN_UP_COUNTER
from coopdrive.runtime.participants import SIMULATOR
from coopdrive.runtime.registry import VEHICLE_STACK
from coopdrive.services.sim.fault_config import TicketExpired
from coopdrive.services.sim.radio_box import RadioPorts
from coopdrive.services.sim.scenario_config import ScenarioConfig, ScenarioError, load_scenario
from coopdrive.services.sim.config import SimConfig
from coopdrive.services.sim.service_crashes import crashed_participants
from coopdrive.v1 import sim_pb2

if TYPE_CHECKING:
    from coopdrive.recording.writer import McapRecorder


class RunOptions(RunSpec):
    """A run (its RunSpec's fields) and what watches it: none of these change what the run computes."""

    model_config = ConfigDict(arbitrary_types_allowed=True)

    # --realtime paces the lockstep run to the wall clock: it is watchable and still deterministic.
    realtime: bool = False
    record: Path | None = None
    gateway_port: int | None = None
    # Serve the run's bus to Foxglove on this WebSocket port (coopdrive.recording.foxglove_live).
    foxglove_port: int | None = None
    # Zenoh endpoints the run's hub listens on besides its own, so other tools (coopdrive record, python-can's
    # coopdrive interface, a zenohd router) can join the run's bus.
    listen: tuple[str, ...] = ()
    log_dir: Path | None = None
    # Called as observer(key, message) for every message on the bus, on Zenoh's thread as it arrives (benchmarks,
    # live tools): a slow one holds the senders back.
    observer: Callable[[str, Message], None] | None = None
    # Called as on_recorded(key, message) for every message the recording takes, from the recording's own thread
    # in its order (a report built from what the recording holds); needs `record`.
    on_recorded: Callable[[str, Message], None] | None = None
    # When the command started (time.monotonic()), for the summary's startup_time_s; None: when run_scenario is
    # called.
    started_monotonic_s: float | None = None
    # Called as on_progress(sim_time_s, duration_s) on the bus's thread at each step of the simulator's clock.
    on_progress: Callable[[float, float], None] | None = None
    # Called as on_process_started(name, pid) for each process the run starts, and starts again after a crash: name
    # is the service's participant ("v1/gateway") or the group's ("v1/group"). For tools watching a process (the
    # gateway bench samples the gateway's memory).
    on_process_started: Callable[[str, int], None] | None = None

    @classmethod
    def of(cls, spec: RunSpec, **watching: Any) -> RunOptions:
        """The run spec describes, watched as `watching` says."""
        return cls(**dict(spec), **watching)


MS_PER_S = 1000
# Certificates of a secured run are valid from a while before the scenario's clock starts.
CERTIFICATE_BACKDATE_S = 3600
# How long the launcher waits for the simulator's result once the simulator has exited.
RESULT_GRACE_S = 5.0
# The process of a run laid out as ProcessLayout.ONE.
ONE_PROCESS_NAME = "run/group"
# What the stacks publish in the last step is spooled after the result: the recording is merged once the spools
# have taken nothing for RECORDING_QUIET_S (at most RECORDING_SETTLE_LIMIT_S).
RECORDING_QUIET_S = 0.2
RECORDING_SETTLE_LIMIT_S = 10.0


def build_specs(options: RunOptions, run_dir: Path | None = None) -> list[ServiceSpec]:
    """Every service's spec. run_dir holds the run's files (GNSS port links, the test PKI); by default a new
    temporary folder the caller removes."""
    run_dir = Path(tempfile.mkdtemp(prefix="coopdrive-run-")) if run_dir is None else run_dir
    source, stacks = checked_run(options, run_dir)
    # --realtime paces the lockstep run to the wall clock: it is watchable and still deterministic.
    sim = SimConfig(scenario=source.name, seed=options.seed, lockstep=True, paced=options.realtime,
                    world_profile=options.world.value)
    ports = iter(free_udp_ports(2 * len(stacks)))
    radio = {vehicle_id: RadioPorts(next(ports), next(ports)) for vehicle_id in stacks}
    sim.scenario_file, sim.stacks = str(source.file), stacks
    sim.radio_links = {vehicle_id: vars(ports) for vehicle_id, ports in radio.items()}
    sim.duration_s, sim.step_s = source.config.duration_s, source.config.step_s
    world_needs = sim.stack_overrides()
    services = VEHICLE_STACK
    # Each stack's GNSS receiver is a pty the simulator writes NMEA to, found through a link in the run folder.
    sim.gnss_ports = {v: str(run_dir / f"{v}-gnss0") for v in stacks}
    # The stacks are told their sensors as they are in the run's world (latencies, the GNSS timing jitter).
    world_config = source.config.in_world(options.world)
    per_vehicle = {v: merged(vehicle_overrides(world_config, v, radio[v]),
                             {"geolocation": {"gnss_port": sim.gnss_ports[v], "serial_sync": "marks"}})
                   for v in stacks}
    if options.security is not None:
        security = secured_run(source.config, stacks, options, run_dir / "pki")
        per_vehicle = {v: merged(per_vehicle[v], {"v2x": security[v]}) for v in stacks}
        sim.security_pki_dir = str(run_dir / "pki")
    if options.duration_s is not None:
        sim.duration_s = options.duration_s
    specs = [ServiceSpec(name, vehicle, merged(merged(world_needs.get(name, {}), per_vehicle.get(vehicle, {}).get(name, {})),
                                               options.overrides_of(name)))
             for vehicle in stacks for name in services]
    sim.participants = [spec.participant for spec in specs]
    sim_config = sim.model_dump(mode="json")
    sim_config.update(options.overrides_of("sim"))
    return [ServiceSpec("sim", WORLD_ID, sim_config)] + specs


def checked_run(spec: RunSpec, run_dir: Path) -> tuple[ScenarioSource, list[str]]:
    """The run's scenario (with its extra faults, written to run_dir) and stack vehicles; ScenarioError, one line,
    for a run that cannot be: what a sweep checks of each of its runs before any starts."""
    source = resolve_scenario(spec.scenario)
    if spec.extra_faults:
        source = source.with_faults(spec.extra_faults, run_dir)
    if spec.security is None and any(isinstance(f, TicketExpired) for f in source.config.faults):
        raise ScenarioError("ticket_expired needs --security: an unsecured run has no tickets to expire")
    stacks = source.stack_vehicles(spec.stacks)
    source.check_roads()
    strangers = sorted(set(spec.untrusted) - set(stacks))
    if strangers:
        raise ScenarioError(f"--untrusted {', '.join(strangers)}: not a stack vehicle of this run ({', '.join(stacks)})")
    return source, stacks


def secured_run(config: ScenarioConfig, stacks: list[str], options: RunOptions, pki_dir: Path) -> dict[str, dict]:
    """A test PKI valid from the scenario's start for the stacks and the simulator's own senders; per stack
    its v2x `security` section."""
    from coopdrive.v2x.security.run_setup import security_overrides
    from coopdrive.v2x.timebase import tai_ms_from_utc

    sim_senders = [v.vehicle_id for v in config.vehicles if v.vehicle_id not in stacks]
    roadside_units = [unit.unit_id for unit in config.roadside_units]
    valid_from_tai_s = tai_ms_from_utc(config.utc_epoch) // MS_PER_S - CERTIFICATE_BACKDATE_S
    overrides = security_overrides(pki_dir, list(stacks) + sim_senders + roadside_units, options.security,
                                   options.untrusted, valid_from_tai_s, roadside_units)
    _expire_tickets(config, pki_dir, options.untrusted, valid_from_tai_s)
    return {vehicle: overrides[vehicle] for vehicle in stacks}


def _expire_tickets(config: ScenarioConfig, pki_dir: Path, untrusted: tuple[str, ...], valid_from_tai_s: int) -> None:
    """ticket_expired faults: the vehicle's tickets in the run's PKI end at the fault's start."""
    from coopdrive.v2x.security.pki import issue_expiring_tickets, load_test_pki
    from coopdrive.v2x.security.run_setup import UNTRUSTED_SUBDIR
    from coopdrive.v2x.timebase import tai_ms_from_utc

    epoch_tai_s = tai_ms_from_utc(config.utc_epoch) // MS_PER_S
    for fault in (f for f in config.faults if isinstance(f, TicketExpired)):
        pki = load_test_pki(pki_dir / UNTRUSTED_SUBDIR if fault.vehicle_id in untrusted else pki_dir)
        if fault.vehicle_id not in pki.tickets:
            raise ScenarioError(f"ticket_expired: {fault.vehicle_id} holds no ticket in this run")
        issue_expiring_tickets(pki, fault.vehicle_id, epoch_tai_s + math.ceil(fault.start_s), valid_from_tai_s)


def _built(options: RunOptions) -> tuple[Path, list[ServiceSpec]]:
    """The run's folder and its services' specs; nothing left behind when it cannot be built."""
    run_dir = Path(tempfile.mkdtemp(prefix="coopdrive-run-"))
    try:
        return run_dir, build_specs(options, run_dir)
    except BaseException:
        shutil.rmtree(run_dir, ignore_errors=True)
        raise


def run_scenario(options: RunOptions) -> sim_pb2.RunResult:
    """ScenarioError (one line) for a run that cannot be built, before anything starts."""
    started = time.monotonic() if options.started_monotonic_s is None else options.started_monotonic_s
    run_dir, specs = _built(options)
    endpoint = loopback_endpoint(free_tcp_port())
    hub = Bus(BusConfig(listen=[endpoint, *options.listen]))
    finished = threading.Event()
    stop_reason: list[str] = []
    results: list[sim_pb2.RunResult] = []

    def on_result(envelope) -> None:
        results.append(envelope.message)
        finished.set()

    def on_signal(signum, _frame) -> None:
        stop_reason.append(signal.Signals(signum).name)
        finished.set()

    # Signals reach only the main thread; a run in a sweep worker's thread is stopped by its worker instead.
    in_main_thread = threading.current_thread() is threading.main_thread()
    previous = {s: signal.signal(s, on_signal) for s in (signal.SIGINT, signal.SIGTERM)} if in_main_thread else {}
    recording, bridge = _watch(options, hub, {spec.participant: json.dumps(spec.config) for spec in specs})
    hub.subscribe(WORLD_ID, "result", on_result)
    give_ups = LockstepGiveUps()
    hub.subscribe_key(DIAGNOSTICS_KEYS, give_ups.observe)
    simulator = next(spec for spec in specs if spec.service == "sim")
    _watch_progress(hub, options, simulator)
    processes, spool_dir, spool_merge = _service_processes(options, endpoint, simulator, run_dir, recording)
    # The simulator says when (service_crash faults, in simulated time); the launcher owns the processes.
    hub.subscribe(WORLD_ID, "service_fault", lambda envelope: carry_out(processes, envelope.message))
    try:
        start_processes(processes, specs, options)
        if options.gateway_port is not None:
            watched = next(spec.vehicle_id for spec in specs if spec.vehicle_id != WORLD_ID)
            processes.start(ServiceSpec("gateway", watched, {"port": options.gateway_port}))
        _wait_for_the_end(processes, finished)
    finally:
        ended = time.monotonic()
        _tear_down(processes, recording, spool_dir, spool_merge, lambda: effective_configs(hub, specs),
                   settle_before_stop=not (stop_reason and not results))
        shutil.rmtree(run_dir, ignore_errors=True)
        if bridge is not None:
            bridge.close()
        hub.close()
        for signum, handler in previous.items():
            signal.signal(signum, handler)
    if not results:
        reason = f"stopped by {stop_reason[0]}" if stop_reason else "the simulator ended without a result"
        results.append(sim_pb2.RunResult(scenario=options.scenario, seed=options.seed, success=False,
                                         failure_reason=reason, wall_time_s=ended - started))
    result = results[0]
    result.metrics[MESSAGES_GIVEN_UP_COUNTER] = give_ups.total()
    if result.clock_started_monotonic_s > 0:
        result.startup_time_s = result.clock_started_monotonic_s - started
    result.shutdown_time_s = time.monotonic() - ended
    return result


def _service_processes(options: RunOptions, endpoint: str, simulator: ServiceSpec, run_dir: Path,
                       recording: Recording | None) -> tuple[ServiceProcesses, Path | None, SpoolMerge | None]:
    """The run's processes; recorded, with the folder of their spools and the merge that follows them."""
    spool_dir = run_dir / "spools" if recording is not None else None
    spool_merge = SpoolMerge(recording.write) if recording is not None else None
    processes = ServiceProcesses(endpoint, clock="sim", log_dir=options.log_dir,
                                 clock_step_s=simulator.config["step_s"], spool_dir=spool_dir,
                                 spool_merge=spool_merge, on_started=options.on_process_started)
    if spool_merge is not None:
        spool_merge.follow()
    return processes, spool_dir, spool_merge


def _watch_progress(hub: Bus, options: RunOptions, simulator: ServiceSpec) -> None:
    """options.on_progress told the simulated time of each step of the simulator's clock."""
    if options.on_progress is not None:
        report_progress, duration_s = options.on_progress, simulator.config["duration_s"]
        hub.subscribe(WORLD_ID, "clock", lambda envelope: report_progress(envelope.message.time_s, duration_s))


def _tear_down(processes: ServiceProcesses, recording: Recording | None, spool_dir: Path | None,
               spool_merge: SpoolMerge | None, configs: Callable[[], dict[str, str]], settle_before_stop: bool) -> None:
    """Stops the services and closes the recording with all they published: the spools were merged into it as
    the run went, and what the last moments added is merged now. At the end of a run the stacks publish their last
    step after the result, so the spools settle before the services stop; stopped by a signal the services would
    go on publishing, so they stop first. A stopped run leaves a whole recording either way."""
    if recording is None:
        processes.stop_all()
        return
    if settle_before_stop:
        _settle(spool_dir)
    recording.recorder.add_configs(configs())
    processes.stop_all()
    spool_merge.finish()  # which warns of each cut spool and each message it leaves out
    recording.recorder.close()


@dataclass
class Recording:
    """The run's recorder and what is told of each message it takes (RunOptions.on_recorded)."""
    recorder: McapRecorder
    on_recorded: Callable[[str, Message], None] | None

    def write(self, key: str, message: Message) -> None:
        self.recorder.write(key, message)
        if self.on_recorded is not None:
            self.on_recorded(key, message)


def _watch(options: RunOptions, hub: Bus, configs: dict[str, dict]):
    """What takes the run's messages besides the launcher: the recording (written from the processes' spools
    as the run goes), the Foxglove bridge and the caller's observer (both live on the bus)."""
    recording = bridge = None
    if options.record is not None or options.foxglove_port is not None:
        from coopdrive.visual import recorded_road_map
    if options.record is not None:
        from coopdrive.recording.writer import McapRecorder

        # The configs go in at the end, as the services ran them (effective_configs); the map is needed now.
        recording = Recording(McapRecorder(options.record, road_map=recorded_road_map(configs)), options.on_recorded)
    if options.foxglove_port is not None:
        from coopdrive.recording.foxglove_live import FoxgloveBridge

        bridge = FoxgloveBridge(hub, options.foxglove_port, road_map=recorded_road_map(configs))
    if options.observer is not None:
        hub.subscribe_key("coopdrive/**", options.observer)
    return recording, bridge


def _settle(spool_dir: Path) -> None:
    """Until the spools have grown by nothing for RECORDING_QUIET_S (at most RECORDING_SETTLE_LIMIT_S)."""
    deadline = time.monotonic() + RECORDING_SETTLE_LIMIT_S
    size = -1
    while time.monotonic() < deadline:
        grown = sum(path.stat().st_size for path in spool_paths(spool_dir))
        if grown == size:
            return
        size = grown
        time.sleep(RECORDING_QUIET_S)


def _wait_for_the_end(processes: ServiceProcesses, finished: threading.Event) -> None:
    """Until the result (or a signal) comes; once the simulator has exited, RESULT_GRACE_S for its result."""
    while not finished.wait(0.2):
        crashed = {name: code for name, code in processes.exited().items()
                   if code != 0 and not name.endswith("/gateway")}
        if processes.process_of[SIMULATOR] in processes.exited():
            finished.wait(RESULT_GRACE_S)
            return
        if crashed and len(crashed) == len(processes.processes):
            raise RunAborted(f"every service exited: {crashed}")


def carry_out(processes: ServiceProcesses, fault: sim_pb2.ServiceFault) -> None:
    """A service_crash falling due: kill the service's process, or start it again."""
    if fault.participant not in processes.process_of:
        return  # not a service of this run: the simulator leaves those out, so a stray message
    if fault.restart:
        processes.restart(fault.participant)
    else:
        processes.kill(fault.participant)


def crashing_participants(specs: list[ServiceSpec]) -> set[str]:
    """The services the run's service_crash faults kill."""
    scenario_file = next(spec for spec in specs if spec.service == "sim").config.get("scenario_file")
    return crashed_participants(load_scenario(scenario_file).faults) if scenario_file else set()


def start_processes(processes: ServiceProcesses, specs: list[ServiceSpec], options: RunOptions) -> None:
    """The services in the processes of options.processes: the simulator alone and each stack as one process
    (`coopdrive group`, the default), one process per service (as on the vehicle), or the simulator and every
    stack in one process. One process per vehicle starts one interpreter instead of six and spends about a third
    less CPU per step than one per service (docs/performance.md); every layout gives the same metrics (a test holds
    it). A service a service_crash kills runs on its own, so that only it dies."""
    crashing = crashing_participants(specs)
    alone = [spec for spec in specs if spec.participant in crashing or options.processes is ProcessLayout.SERVICE
             or (options.processes is ProcessLayout.VEHICLE and spec.vehicle_id == WORLD_ID)]
    grouped = [spec for spec in specs if spec not in alone]
    if options.processes is ProcessLayout.ONE and grouped:
        processes.start_group(ONE_PROCESS_NAME, grouped)
    else:
        for vehicle_id in dict.fromkeys(spec.vehicle_id for spec in grouped):
            processes.start_group(f"{vehicle_id}/group", [spec for spec in grouped if spec.vehicle_id == vehicle_id])
    for spec in alone:
        processes.start(spec)


def effective_configs(hub: Bus, specs: list[ServiceSpec]) -> dict[str, str]:
    """The config each service actually ran with, for the recording: as the running services tell it (their
    `_info` queryables); a service that does not answer (crashed, never started) by its class's defaults
    completed by the spec. Asked at the end, so the launcher never imports the services' code (filterpy, scipy)
    while they start."""
    from coopdrive.recording.live_configs import ServiceConfigCollector

    collector = ServiceConfigCollector(hub)
    collector.collect()
    told = collector.stop(ask_again=False)
    return {spec.participant: told.get(spec.participant) or _full_config(spec) for spec in specs}


def _full_config(spec: ServiceSpec) -> str:
    """The config a service will actually run with: its defaults completed by the spec."""
    from coopdrive.runtime.registry import service_class

    model = service_class(spec.service).Config.model_validate(spec.config)
    return json.dumps(model.model_dump(mode="json"))
