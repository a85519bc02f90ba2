"""Where a run's CPU goes: each process's CPU to start (imports, joining) and per simulated second of stepping.

    .venv/bin/python -m bench.profile_run follow --duration 30
    .venv/bin/python -m bench.profile_run string --stacks 8 --duration 10

The CPU of the launcher's descendants is read from /proc (user + system time, every thread, Zenoh's native ones too) every
POLL_S until the run ends, so the last POLL_S of each process is not counted. docs/performance.md says how the
figures there were made; for where inside a process the time goes, run the same command under
`py-spy record --gil --subprocesses`.
"""

from __future__ import annotations

import argparse
import os
import threading
import time
from pathlib import Path

from rich.console import Console
from rich.table import Table

from coopdrive.launch.process_layout import ProcessLayout
from coopdrive.launch.run import RunOptions, run_scenario

POLL_S = 0.2
CLOCK_TICKS_PER_S = os.sysconf("SC_CLK_TCK")


def _stat_fields(pid: int) -> list[str]:
    # The command name (field 2) may hold spaces and parentheses: the fields after it follow the last ")".
    return Path(f"/proc/{pid}/stat").read_text().rsplit(")", 1)[1].split()


def _descendants_cpu_s(root_pid: int) -> dict[int, tuple[str, float]]:
    """pid -> (command line, CPU seconds) of every living descendant of root_pid: the services are children of
    the fork server (forked_process.py), itself a child of the launcher."""
    found: dict[int, tuple[int, str, float]] = {}  # pid -> (parent, command line, CPU s)
    for entry in Path("/proc").iterdir():
        if not entry.name.isdigit():
            continue
        try:
            fields = _stat_fields(int(entry.name))
            command = (entry / "cmdline").read_bytes().replace(b"\0", b" ").decode(errors="replace")
        except (OSError, IndexError, ValueError):
            continue  # it ended while we looked
        found[int(entry.name)] = (int(fields[1]), command, (int(fields[11]) + int(fields[12])) / CLOCK_TICKS_PER_S)
    descendants: dict[int, tuple[str, float]] = {}
    parents = {root_pid}
    while parents:
        children = {pid for pid, (parent, _, _) in found.items() if parent in parents and pid not in descendants}
        descendants.update({pid: found[pid][1:] for pid in children})
        parents = children
    return descendants


def process_label(command: str) -> str:
    """"coopdrive.cli service scene --vehicle ego ..." -> "ego/scene"; a group -> "<spec file> group"."""
    words = command.split()
    if "from multiprocessing." in command:  # the fork server or its resource tracker
        return "multiprocessing " + command.split("from multiprocessing.", 1)[1].split()[0]
    if "service" in words:
        name = words[words.index("service") + 1]
        vehicle = words[words.index("--vehicle") + 1] if "--vehicle" in words else "?"
        return f"{vehicle}/{name}"
    if "group" in words:
        return Path(words[words.index("group") + 1]).stem.replace("-group", "/group")
    return command[:40]


def profile(options: RunOptions) -> tuple[object, dict[str, tuple[float, float]], float]:
    """Runs the scenario; returns its result, per process label (start-up CPU s, stepping CPU s), and the
    launcher's CPU seconds. Start-up is each process's CPU at the last look before step 0."""
    last: dict[int, tuple[str, float]] = {}
    at_step_zero: dict[int, float] = {}
    looks: list[tuple[float, dict[int, float]]] = []
    done = threading.Event()

    def poll() -> None:
        while not done.wait(POLL_S):
            seen = _descendants_cpu_s(os.getpid())
            for pid, (command, cpu_s) in seen.items():
                # A forked service retitles itself once it runs (forked_process.py); an ended process not yet
                # reaped still tells its CPU, but no longer its command line.
                last[pid] = (command if command or pid not in last else last[pid][0], cpu_s)
            looks.append((time.monotonic(), {pid: cpu_s for pid, (_, cpu_s) in seen.items()}))

    poller = threading.Thread(target=poll, daemon=True)
    poller.start()
    launcher_started_cpu_s = time.process_time()
    result = run_scenario(options)
    launcher_cpu_s = time.process_time() - launcher_started_cpu_s
    done.set()
    poller.join()
    for looked_at, cpu_by_pid in looks:
        if looked_at <= result.clock_started_monotonic_s:
            at_step_zero.update(cpu_by_pid)
    per_process: dict[str, tuple[float, float]] = {}
    for pid, (command, cpu_s) in last.items():
        label = process_label(command)
        startup_s, stepping_s = per_process.get(label, (0.0, 0.0))
        started_s = at_step_zero.get(pid, 0.0)
        per_process[label] = (startup_s + started_s, stepping_s + cpu_s - started_s)
    return result, per_process, launcher_cpu_s


def main(argv: list[str] | None = None) -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("scenario")
    parser.add_argument("--stacks", type=int)
    parser.add_argument("--duration", type=float, default=30.0)
    parser.add_argument("--processes", choices=[layout.value for layout in ProcessLayout], default="vehicle")
    args = parser.parse_args(argv)
    result, per_process, launcher_cpu_s = profile(RunOptions(scenario=args.scenario, stacks=args.stacks,
                                                             duration_s=args.duration,
                                                             processes=ProcessLayout(args.processes)))
    sim_s = max(result.sim_time_s, 1e-9)
    table = Table(title=f"{args.scenario}: {sim_s:.0f} s simulated in {result.wall_time_s:.2f} s "
                        f"(real-time factor {sim_s / max(result.wall_time_s, 1e-9):.2f}); start-up "
                        f"{result.startup_time_s:.2f} s, shut-down {result.shutdown_time_s:.2f} s")
    for column in ("process", "start-up CPU s", "stepping CPU s", "stepping CPU ms per simulated s"):
        table.add_column(column, justify="left" if column == "process" else "right")
    for label, (startup_s, stepping_s) in sorted(per_process.items(), key=lambda item: -item[1][1]):
        table.add_row(label, f"{startup_s:.2f}", f"{stepping_s:.2f}", f"{1000 * stepping_s / sim_s:.0f}")
    startup_total_s = sum(startup for startup, _ in per_process.values())
    stepping_total_s = sum(stepping for _, stepping in per_process.values())
    table.add_row("all services", f"{startup_total_s:.2f}", f"{stepping_total_s:.2f}",
                  f"{1000 * stepping_total_s / sim_s:.0f}")
    table.add_row("launcher (whole run)", "", f"{launcher_cpu_s:.2f}", "")
    Console().print(table)


if __name__ == "__main__":
    main()
