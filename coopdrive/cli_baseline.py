"""`coopdrive run SCENARIO --baseline NAME`: our run, then the baseline (the same run on a reference CACC law, or
the scenario's platoon under Plexe's controllers in SUMO), and both side by side; ours must damp at least as well."""

from __future__ import annotations

import json

from coopdrive.exit_status import EXIT_FAILED, EXIT_OK
from coopdrive.launch.plexe_files import SUMO_PLEXE


def baseline_choices() -> list[str]:
    """Every CACC law, and Plexe's controllers in SUMO."""
    from coopdrive.services.control.longitudinal import CaccLaw

    return [law.value for law in CaccLaw] + [SUMO_PLEXE]


def plexe_setup(options):
    """The Plexe baseline of the run, checked before anything starts (PlexeBaselineError: one line)."""
    from coopdrive.launch.plexe_baseline import PlexeString, sumo_library
    from coopdrive.launch.scenario_source import resolve_scenario

    sumo_library()
    return PlexeString.of(resolve_scenario(options.scenario).config, options.duration_s, options.seed)


def compare_with_law(args, options, result, recorded_to, run_once) -> int:
    """The run again with every stack on the law args.baseline names (run_once(options, report, record))."""
    from coopdrive.launch.baseline import BaselineComparison, with_cacc_law
    from coopdrive.services.control.longitudinal import CaccLaw

    law = CaccLaw(args.baseline)
    baseline_options = with_cacc_law(options, law).model_copy(update={"record": None, "gateway_port": None,
                                                                      "foxglove_port": None, "listen": ()})
    baseline_report = None if args.report is None else args.report / "baseline"
    baseline, baseline_recorded_to = run_once(baseline_options, baseline_report, None)
    comparison = BaselineComparison.of(law, result, baseline)
    return _tell(args, result, recorded_to, comparison,
                 (baseline, baseline_recorded_to, f", every stack on the {law.value} CACC"))


def compare_with_plexe(args, result, recorded_to, plexe) -> int:
    """The scenario's platoon under Plexe's controllers in SUMO (plexe: plexe_setup's)."""
    from coopdrive.launch.baseline import BaselineComparison
    from coopdrive.launch.plexe_baseline import run_plexe_string

    metrics = run_plexe_string(plexe).metrics(plexe)
    comparison = BaselineComparison(SUMO_PLEXE, dict(result.metrics), metrics, plexe.description())
    return _tell(args, result, recorded_to, comparison, None)


def _tell(args, result, recorded_to, comparison, baseline_run) -> int:
    """Both runs' figures, as JSON or tables; baseline_run: (its result, recording, label) when it was a run of
    ours."""
    from coopdrive.launch.summary import print_summary, summary_dict

    passed = result.success and comparison.ours_no_worse
    if args.json:
        summary = summary_dict(result)
        summary["baseline"] = comparison.as_dict()
        if baseline_run is not None:
            summary["baseline"]["run"] = summary_dict(baseline_run[0])
        summary["success"] = passed
        if not comparison.ours_no_worse:
            summary["failure_reason"] = comparison.failure_reason()
        print(json.dumps(summary, indent=2))
    else:
        print_summary(result, recording=recorded_to)
        if baseline_run is not None:
            baseline, baseline_recorded_to, label = baseline_run
            print_summary(baseline, recording=baseline_recorded_to, label=label)
        comparison.print()
    return EXIT_OK if passed else EXIT_FAILED
