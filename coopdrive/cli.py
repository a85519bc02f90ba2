"""The `coopdrive` command line: thin wiring from arguments to the library."""

from __future__ import annotations

import argparse
import gc
import json
import sys
import time
from pathlib import Path

from coopdrive.cli_baseline import SUMO_PLEXE, baseline_choices, compare_with_law, compare_with_plexe, plexe_setup
from coopdrive.cli_deploy import add_commands as add_deploy_commands
from coopdrive.cli_judging import add_commands as add_judging_commands
from coopdrive.cli_recording import add_commands as add_recording_commands
from coopdrive.cli_service import add_commands as add_service_commands
from coopdrive.cli_service import run_command
from coopdrive.exit_status import EXIT_FAILED, EXIT_INCOMPLETE, EXIT_OK, EXIT_USAGE
from coopdrive.launch.process_layout import ProcessLayout
from coopdrive.services.planner.cli import add_v2x_commands as add_planner_v2x_commands
from coopdrive.services.v2x.cli import add_commands as add_v2x_commands
from coopdrive.runtime.config import ConfigError

# A run's start-up time is counted from here: the command as its user waits for it, less the interpreter's start.
COMMAND_STARTED_MONOTONIC_S = time.monotonic()


def main(argv: list[str] | None = None) -> int:
    return run_command(build_parser(), argv)


def entry() -> int:
    """The `coopdrive` command: main(), and then the interpreter's last garbage collection is left out (gc.freeze).
    The command has closed what it opened by then, and that collection over every object of the stack was most of a
    stopped run's exit: a realtime run with its gateway exited 0.52 s after SIGTERM, 0.22 s without it. Not in main,
    which tests call in their own process."""
    code = main()
    gc.freeze()
    return code


def build_parser() -> argparse.ArgumentParser:
    parser = argparse.ArgumentParser(prog="coopdrive", description="Cooperative automated driving stack")
    commands = parser.add_subparsers(dest="command", required=True)
    add_service_commands(commands)  # service, group
    _add_run_command(commands)
    add_judging_commands(commands)  # score, analyze, scenarios, candump
    add_planner_v2x_commands(add_v2x_commands(commands))  # v2x decode, send, replay; advise
    add_recording_commands(commands)  # record, import, replay, export
    add_deploy_commands(commands)  # health, router, foxglove
    return parser


def _add_run_command(commands) -> None:
    run = commands.add_parser("run", help="run a scenario with the full stack")
    run.add_argument("scenario", help="a scenario name (see `coopdrive scenarios`), a YAML file, or `all`")
    run.add_argument("--seed", type=int, help="the run's random seed (for several, --seeds)")
    run.add_argument("--seeds", metavar="A-B", help="run every seed of a range (e.g. 1-20 or 1,4,7-9) in parallel")
    run.add_argument("--stacks", type=int, metavar="N", help="run the stack on the first N stack vehicles only")
    run.add_argument("--world", choices=["real", "ideal"], default="real",
                     help="real: every sensor's and the radio's error sources (the default); ideal: none of them, "
                          "for runs that need exact answers (services/sim/README.md)")
    run.add_argument("--workers", type=int, default=2,
                     help="parallel runs for `all` and --seeds: the local Dask cluster's worker processes")
    run.add_argument("--cluster", metavar="ADDRESS",
                     help="run `all`/--seeds on this Dask scheduler's workers (tcp://host:8786), not a local cluster")
    run.add_argument("--faults", type=Path, metavar="FILE",
                     help="sweep these fault variants too (YAML: name -> faults, as docs/sweep-faults.yaml)")
    run.add_argument("--out", type=Path, metavar="DIR",
                     help="batch runs: metrics.json and the report per run, and summary files")
    run.add_argument("--time-limit", type=float, metavar="SECONDS",
                     help="batch runs: stop this long after the sweep started (its cluster's start counted), cancel "
                          "the runs not finished and list them; exit status 4 when every run that finished passed")
    run.add_argument("--no-reports", dest="reports", action="store_false",
                     help="batch runs with --out: metrics.json per run and the summary files only, no recording or "
                          "plots (a run spends a tenth less; CI's sweep)")
    run.add_argument("--processes", choices=[layout.value for layout in ProcessLayout],
                     help="one process per vehicle's stack (a single run's default), one per service as on the "
                          "vehicle, or one for the simulator and every stack (a sweep's default: its runs fill the "
                          "cores already)")
    run.add_argument("--security", choices=[m.value for m in _security_modes()],
                     help="V2X security of every stack (ETSI TS 103 097): each gets tickets from a test PKI")
    run.add_argument("--untrusted", action="append", default=[], metavar="VEHICLE",
                     help="with --security: this stack vehicle holds a ticket from a root nobody trusts")
    run.add_argument("--cacc-law", choices=[law.value for law in _cacc_laws()],
                     help="the cooperative law of every stack (default: each stack's control config, ours)")
    run.add_argument("--baseline", choices=baseline_choices(), metavar="NAME",
                     help="run again with every stack on this CACC law (e.g. ploeg), or the platoon under Plexe's "
                          f"controllers in SUMO ({SUMO_PLEXE}), and compare: ours must damp at least as well "
                          f"(choices: {', '.join(baseline_choices())})")
    run.add_argument("--v2v-loss", type=float, metavar="P",
                     help="lose every V2V packet with probability P (0-1), independently, on top of the scenario")
    run.add_argument("--v2v-cut-at", type=float, metavar="SECONDS", help="cut every V2V link from this time on")
    run.add_argument("--fault", action="append", default=[], metavar="YAML",
                     help="add a fault to the scenario's, as in its faults list, e.g. "
                          "'{type: iclcm_drop, vehicle_id: a2, flag: merge_request, start_s: 0}'")
    run.add_argument("--set", action="append", default=[], metavar="SERVICE.KEY=VALUE", dest="settings",
                     help="change a config key of a service in every stack (or of the simulator: sim.KEY), e.g. "
                          "planner.glosa=false; checked against the service's config before anything starts")
    run.add_argument("--realtime", action="store_true", help="pace the simulation to wall time")
    run.add_argument("--record", type=Path, metavar="FILE.mcap")
    run.add_argument("--gateway", type=int, metavar="PORT", help="serve the gateway HTTP API on this port")
    run.add_argument("--foxglove", type=int, metavar="PORT", help="serve the run to Foxglove (WebSocket) on this port")
    run.add_argument("--listen", action="append", default=[], metavar="ENDPOINT",
                     help="the run's bus also listens here (e.g. tcp/127.0.0.1:7447) for other tools to join")
    run.add_argument("--duration", type=float, help="simulated seconds (default: the scenario's)")
    run.add_argument("--logs", type=Path, help="folder for each process's log (<vehicle>-group.log, or <vehicle>-<service>.log)")
    run.add_argument("--json", action="store_true", help="print the summary as JSON")
    run.add_argument("--report", type=Path, metavar="DIR",
                     help="write metrics.json, plots and index.html to DIR (records to DIR/run.mcap without --record)")
    run.set_defaults(handler=_run)


def _run(args) -> int:
    from coopdrive.launch.run import RunOptions
    from coopdrive.launch.run_spec import RunSpec
    from coopdrive.launch.plexe_files import PlexeBaselineError
    from coopdrive.services.sim.scenario_config import ScenarioError

    if args.scenario == "all" or args.seeds or args.faults or args.cluster:
        return _batch(args)
    sweep_flags = [flag for flag, given in SWEEP_FLAGS.items() if given(args)]
    if sweep_flags:
        print(f"coopdrive: {', '.join(sweep_flags)}: for a sweep (--seeds or all), not a single run (--report DIR "
              "writes one run's report)", file=sys.stderr)
        return EXIT_USAGE
    if args.untrusted and args.security is None:
        print("coopdrive: --untrusted needs --security", file=sys.stderr)
        return EXIT_USAGE
    spec = _run_spec(args, scenario=args.scenario, seed=_seed(args), processes=_layout(args, RunSpec().processes),
                     untrusted=tuple(args.untrusted))
    options = RunOptions.of(spec, realtime=args.realtime, record=args.record, gateway_port=args.gateway,
                            foxglove_port=args.foxglove, listen=tuple(args.listen), log_dir=args.logs,
                            started_monotonic_s=COMMAND_STARTED_MONOTONIC_S)
    try:
        # A run that cannot be built (a bad scenario file, --stacks, a fault, a baseline) stops before anything starts.
        plexe = plexe_setup(options) if args.baseline == SUMO_PLEXE else None
        if args.baseline is None:
            return _run_and_tell(args, options)
        result, recorded_to = _run_once(options, args.report, args.record)
    except (ScenarioError, PlexeBaselineError) as error:
        print(f"coopdrive: {error}", file=sys.stderr)
        return EXIT_USAGE
    if plexe is not None:
        return compare_with_plexe(args, result, recorded_to, plexe)
    return compare_with_law(args, options, result, recorded_to, _run_once)


def _run_and_tell(args, options) -> int:
    """One run: its summary as JSON, or its story with a progress line while it runs."""
    if args.json:
        from coopdrive.launch.summary import summary_dict

        result, _ = _run_once(options, args.report, args.record)
        print(json.dumps(summary_dict(result), indent=2))
        return EXIT_OK if result.success else EXIT_FAILED
    from coopdrive.launch.progress_line import ProgressLine
    from coopdrive.launch.run_story import tell
    from coopdrive.launch.scenario_source import resolve_scenario

    progress = ProgressLine()
    try:
        result, recorded_to = _run_once(options.model_copy(update={"on_progress": progress.update}), args.report,
                                        args.record)
    finally:
        progress.close()
    tell(result, resolve_scenario(options.scenario).config.description, recorded_to, args.report)
    return EXIT_OK if result.success else EXIT_FAILED


def service_settings(assignments: list[str]) -> dict[str, dict]:
    """--set SERVICE.KEY=VALUE as {service: overrides}, each service's overrides validated against its config."""
    from coopdrive.bus.services import SERVICE_NAMES
    from coopdrive.runtime.config import apply_override, validate_config
    from coopdrive.runtime.registry import service_class

    overrides: dict[str, dict] = {}
    for assignment in assignments:
        service, _, setting = assignment.partition(".")
        if service not in SERVICE_NAMES or not setting:
            raise ConfigError(f"--set {assignment!r}: expected SERVICE.KEY=VALUE, SERVICE one of "
                              f"{', '.join(SERVICE_NAMES)}")
        apply_override(overrides.setdefault(service, {}), setting)
    for service, data in overrides.items():
        validate_config(service_class(service).Config, data, f"--set {service}")
    return overrides


def _run_spec(args, **given):
    """The run the arguments describe (what a single run and every run of a sweep share, and `given`), validated
    here once: a bad value is one line naming its option."""
    from pydantic import ValidationError

    from coopdrive.launch.run_spec import RunSpec

    fields = dict(duration_s=args.duration, stacks=args.stacks, world=args.world, security=args.security,
                  cacc_law=args.cacc_law, extra_faults=_extra_faults(args),
                  service_overrides=service_settings(args.settings), **given)
    try:
        return RunSpec(**fields)
    except ValidationError as error:
        first = error.errors()[0]
        option = OPTION_OF_FIELD.get(str(first["loc"][0]), str(first["loc"][0]))
        raise ConfigError(f"{option} {first.get('input')!r}: {first['msg'].lower()}") from None


# The run-spec fields a user sets through an option of another name.
OPTION_OF_FIELD = {"duration_s": "--duration", "stacks": "--stacks", "seed": "--seed", "cacc_law": "--cacc-law"}


def _extra_faults(args) -> tuple[dict, ...]:
    """--v2v-loss and --v2v-cut-at as scenario faults on every vehicle's radio, and each --fault as written;
    the scenario's validation names whatever in them is wrong."""
    import yaml

    faults = []
    if args.v2v_loss is not None and not 0.0 <= args.v2v_loss <= 1.0:
        raise ConfigError(f"--v2v-loss {args.v2v_loss}: a probability from 0 to 1")
    if args.v2v_cut_at is not None and args.v2v_cut_at < 0:
        raise ConfigError(f"--v2v-cut-at {args.v2v_cut_at}: a time from the start of the run, 0 or later")
    if args.v2v_loss is not None:
        faults.append({"type": "v2v_loss", "start_s": 0.0, "loss_probability": args.v2v_loss})
    if args.v2v_cut_at is not None:
        faults.append({"type": "v2v_loss", "start_s": args.v2v_cut_at, "loss_probability": 1.0})
    for text in args.fault:
        try:
            fault = yaml.safe_load(text)
        except yaml.YAMLError as error:
            raise ConfigError(f"--fault {text!r}: not YAML ({error.problem})") from None
        if not isinstance(fault, dict):
            raise ConfigError(
                f"--fault {text!r}: a mapping such as '{{type: gnss_outage, vehicle_id: ego, start_s: 5}}'")
        faults.append(fault)
    return tuple(faults)


def _run_once(options, report: Path | None, record: Path | None):
    """One run, with a report when asked; returns the result and where it was recorded."""
    from coopdrive.launch.run import run_scenario

    if report is None:
        return run_scenario(options), record
    from coopdrive.judging.commands import RECORDING_FILE, report_notice, run_with_report

    result = run_with_report(options, report)
    report_notice(report)
    return result, record or report / RECORDING_FILE


def _seed(args) -> int:
    """--seed, or a run's default seed."""
    from coopdrive.launch.run_spec import RunSpec

    return RunSpec().seed if args.seed is None else args.seed


def _layout(args, default: ProcessLayout) -> ProcessLayout:
    """--processes, or the default of a single run or a sweep (RunSpec's, BatchOptions')."""
    return default if args.processes is None else ProcessLayout(args.processes)


# What `coopdrive run` does for one run only, by whether it was given: a sweep would otherwise run without it.
# (SWEEP_FLAGS: the other way round.)
SINGLE_RUN_FLAGS = {
    "--realtime": lambda args: args.realtime, "--record": lambda args: args.record is not None,
    "--gateway": lambda args: args.gateway is not None, "--foxglove": lambda args: args.foxglove is not None,
    "--listen": lambda args: bool(args.listen), "--logs": lambda args: args.logs is not None,
    "--json": lambda args: args.json, "--report": lambda args: args.report is not None,
    "--baseline": lambda args: args.baseline is not None,
}
SWEEP_FLAGS = {"--out": lambda args: args.out is not None, "--no-reports": lambda args: not args.reports,
               "--time-limit": lambda args: args.time_limit is not None}


def _batch(args) -> int:
    from coopdrive.launch.batch import BatchOptions, parse_seeds, scenario_names
    from coopdrive.launch.sweep import run_batch
    from coopdrive.launch.sweep_cluster import SweepError
    from coopdrive.launch.sweep_faults import NO_FAULTS, FaultsFileError, load_fault_variants
    from coopdrive.services.sim.scenario_config import ScenarioError

    try:
        if args.seeds and args.seed is not None:
            print(f"coopdrive: --seed {args.seed} and --seeds {args.seeds}: give one of them", file=sys.stderr)
            return EXIT_USAGE
        seeds = parse_seeds(args.seeds) if args.seeds else [_seed(args)]
        variants = load_fault_variants(args.faults) if args.faults else {NO_FAULTS: ()}
    except FaultsFileError as error:
        print(f"coopdrive: --faults {error}", file=sys.stderr)
        return EXIT_USAGE
    except ValueError as error:
        print(f"coopdrive: --seeds: {error}", file=sys.stderr)
        return EXIT_USAGE
    if args.time_limit is not None and not args.time_limit > 0:
        print(f"coopdrive: --time-limit {args.time_limit:g}: give the seconds the sweep may take (above 0)",
              file=sys.stderr)
        return EXIT_USAGE
    scenarios = scenario_names() if args.scenario == "all" else [args.scenario]
    if args.untrusted:
        print("coopdrive: --untrusted is for single runs (name the vehicle of one scenario)", file=sys.stderr)
        return EXIT_USAGE
    single_run_flags = [flag for flag, given in SINGLE_RUN_FLAGS.items() if given(args)]
    if single_run_flags:
        print(f"coopdrive: {', '.join(single_run_flags)}: for a single run, not a sweep (--out DIR keeps each run's "
              "report and recording)", file=sys.stderr)
        return EXIT_USAGE
    # --fault and --v2v-* go in every run, before each variant's own faults.
    run = _run_spec(args, processes=_layout(args, BatchOptions.run.processes))
    options = BatchOptions(scenarios=scenarios, seeds=seeds, run=run.model_copy(update={"extra_faults": ()}),
                           workers=args.workers, out_dir=args.out,
                           fault_variants={name: run.extra_faults + faults for name, faults in variants.items()},
                           cluster=args.cluster, reports=args.reports, time_limit_s=args.time_limit)
    try:
        summary = run_batch(options)
    except (ScenarioError, SweepError) as error:
        print(f"coopdrive: {error}", file=sys.stderr)
        return EXIT_USAGE
    return sweep_exit_status(summary)


def sweep_exit_status(summary) -> int:
    """EXIT_OK: every run finished and passed; EXIT_INCOMPLETE: the time limit stopped the sweep and every run that
    finished passed; EXIT_FAILED: a run failed, or Ctrl-C stopped the sweep."""
    from coopdrive.launch.batch import SweepEnd

    if summary.all_passed:
        return EXIT_OK
    if summary.end is SweepEnd.TIME_LIMIT and all(o.success for o in summary.outcomes):
        return EXIT_INCOMPLETE
    return EXIT_FAILED


def _cacc_laws():
    from coopdrive.services.control.longitudinal import CaccLaw

    return list(CaccLaw)


def _security_modes():
    from coopdrive.v2x.security.profile import SecurityMode

    return list(SecurityMode)


def _following_laws():
    from coopdrive.services.control.string_stability import FollowingLaw

    return list(FollowingLaw)


if __name__ == "__main__":
    sys.exit(entry())
