"""COOPDRIVE_HANDLER_CPU_DIR makes every service write the CPU of each of its handlers when it stops, a nested
handler's part charged to it alone; bench.profile_handlers adds the ledgers of a run up by service and handler."""

import csv

import pytest

from bench.profile_handlers import RUNTIME_ROW, main, read_ledgers
from coopdrive.launch.process_layout import ProcessLayout
from coopdrive.launch.run import RunOptions, run_scenario
from coopdrive.runtime import handler_ledger
from coopdrive.runtime.handler_ledger import HANDLER_CPU_DIR_VARIABLE, HandlerLedger, handler_name
from coopdrive.runtime.timers import TimeTrigger
from services.sim.config import SimConfig


class FakeCpuClock:
    """time.thread_time for the ledger, moved on by the handlers themselves: exact charges to assert."""

    def __init__(self):
        self.now_s = 0.0

    def thread_time(self) -> float:
        return self.now_s


@pytest.fixture
def clock(monkeypatch) -> FakeCpuClock:
    fake = FakeCpuClock()
    monkeypatch.setattr(handler_ledger.time, "thread_time", fake.thread_time)
    return fake


def test_each_call_of_a_handler_is_counted_and_its_cpu_charged_to_its_row(tmp_path, clock):
    ledger = HandlerLedger(tmp_path / "ego-scene.handlers.csv")

    def on_cam(envelope):
        clock.now_s += 0.25

    charged = ledger.timed("topic", "v2x/cam", on_cam)
    for _ in range(3):
        charged(None)
    cost = ledger.costs["topic", "v2x/cam"]
    assert (cost.calls, cost.cpu_s) == (3, 0.75)


def test_the_longest_call_of_a_handler_is_kept_beside_its_sum(tmp_path, clock):
    ledger = HandlerLedger(tmp_path / "ego-scene.handlers.csv")
    charged = ledger.timed("timer", "publish_scene",
                           lambda now_s, cost_s: setattr(clock, "now_s", clock.now_s + cost_s))
    for cost_s in (0.25, 2.0, 0.5):
        charged(0.0, cost_s=cost_s)
    cost = ledger.costs["timer", "publish_scene"]
    assert (cost.calls, cost.cpu_s, cost.longest_call_cpu_s) == (3, 2.75, 2.0)


def test_a_handler_run_inside_another_is_charged_to_itself_and_not_again_to_the_outer_one(tmp_path, clock):
    ledger = HandlerLedger(tmp_path / "ego-scene.handlers.csv")
    inner = ledger.timed("topic", "v2x/cam", lambda envelope: setattr(clock, "now_s", clock.now_s + 5.0))

    def outer_handler(now_s):
        clock.now_s += 1.0
        inner(None)
        clock.now_s += 2.0

    ledger.timed("timer", "publish_scene", outer_handler)(0.0)
    assert ledger.costs["timer", "publish_scene"].cpu_s == 3.0
    assert ledger.costs["topic", "v2x/cam"].cpu_s == 5.0


def test_a_handler_that_raises_is_still_charged_and_its_error_goes_on_to_the_runner(tmp_path, clock):
    ledger = HandlerLedger(tmp_path / "ego-scene.handlers.csv")

    def malformed(envelope):
        clock.now_s += 0.5
        raise ValueError("bad CAM")

    with pytest.raises(ValueError, match="bad CAM"):
        ledger.timed("topic", "v2x/cam", malformed)(None)
    assert (ledger.costs["topic", "v2x/cam"].calls, ledger.costs["topic", "v2x/cam"].cpu_s) == (1, 0.5)


def test_a_timed_timer_keeps_its_handler_s_name_for_its_overruns_and_failures(tmp_path):
    class Scene:
        def publish_scene(self, now_s):
            pass

    handler = Scene().publish_scene
    timed = HandlerLedger(tmp_path / "ego-scene.handlers.csv").timed("timer", handler_name(handler), handler)
    assert TimeTrigger(0.04, timed).name == TimeTrigger(0.04, handler).name == "publish_scene"
    assert handler_name(handler) == "test_a_timed_timer_keeps_its_handler_s_name_for_its_overruns_and_failures." \
                                    "<locals>.Scene.publish_scene"


def test_the_ledger_file_lists_the_handlers_most_cpu_first_and_ends_with_the_worker_s_cpu(tmp_path, clock):
    ledger = HandlerLedger(tmp_path / "out" / "ego-scene.handlers.csv")
    for name, cost_s in (("ego/state", 0.1), ("v2x/cam", 0.7)):
        ledger.timed("topic", name, lambda envelope, cost_s=cost_s: setattr(clock, "now_s", clock.now_s + cost_s))(None)
    ledger.write(worker_cpu_s=1.0)
    with ledger.out_file.open(newline="") as written:
        rows = list(csv.DictReader(written))
    assert [(row["kind"], row["name"], row["calls"]) for row in rows] == [
        ("topic", "v2x/cam", "1"), ("topic", "ego/state", "1"), ("worker", "worker", "")]
    assert [float(row["cpu_s"]) for row in rows] == pytest.approx([0.7, 0.1, 1.0])
    assert [row["longest_call_cpu_s"] for row in rows][2] == ""
    assert [float(row["longest_call_cpu_s"]) for row in rows[:2]] == pytest.approx([0.7, 0.1])


def test_a_ledger_that_cannot_be_written_is_named_in_a_warning_and_raises_nothing(tmp_path, caplog):
    (tmp_path / "a file").write_text("not a folder")
    HandlerLedger(tmp_path / "a file" / "ego-scene.handlers.csv").write(worker_cpu_s=1.0)
    assert "COOPDRIVE_HANDLER_CPU_DIR=" in caplog.text and "could not be written" in caplog.text


def test_without_the_variable_a_service_keeps_no_ledger(monkeypatch):
    monkeypatch.delenv(HANDLER_CPU_DIR_VARIABLE, raising=False)
    assert HandlerLedger.from_environment("ego-scene") is None


def write_ledger(path, rows, worker_cpu_s):
    with path.open("w", newline="") as out:
        writer = csv.writer(out)
        writer.writerow(handler_ledger.CSV_COLUMNS)
        writer.writerows(row + (row[3] / 2,) for row in rows)
        writer.writerow(("worker", "worker", "", worker_cpu_s, ""))


def test_the_table_sums_a_service_s_handler_over_the_vehicles_and_gives_each_service_its_runtime(tmp_path):
    write_ledger(tmp_path / "a1-scene.handlers.csv", [("topic", "v2x/cam", 10, 0.5)], 0.75)
    write_ledger(tmp_path / "a-2-scene.handlers.csv", [("topic", "v2x/cam", 30, 1.5)], 2.0)
    write_ledger(tmp_path / "world-sim.handlers.csv", [("timer", "ScenarioFeed.on_step", 50, 3.0)], 3.25)
    rows = {(row.service, row.handler): (row.calls, row.cpu_s, row.longest_call_cpu_s)
            for row in read_ledgers(tmp_path)}
    # The longest call is the longest on any vehicle (the test's ledgers say half of each row's CPU).
    assert rows == {("sim", "timer ScenarioFeed.on_step"): (50, 3.0, 1.5), ("scene", "topic v2x/cam"): (40, 2.0, 0.75),
                    ("scene", RUNTIME_ROW): (0, pytest.approx(0.75), 0.0), ("sim", RUNTIME_ROW): (0, 0.25, 0.0)}


def test_the_command_prints_the_table_per_simulated_second_and_names_a_folder_with_no_ledgers(tmp_path, capsys):
    write_ledger(tmp_path / "world-sim.handlers.csv", [("timer", "ScenarioFeed.on_step", 50, 3.0)], 3.25)
    main([str(tmp_path), "--simulated-s", "10"])
    out = capsys.readouterr().out
    assert "ScenarioFeed.on_step" in out and "92.3 %" in out and "300" in out
    (tmp_path / "empty").mkdir()
    with pytest.raises(SystemExit):
        main([str(tmp_path / "empty")])
    assert "holds no *.handlers.csv: was COOPDRIVE_HANDLER_CPU_DIR set for the run?" in capsys.readouterr().err


def test_a_run_with_the_variable_writes_every_service_s_ledger_and_the_table_reads_them(tmp_path, monkeypatch):
    monkeypatch.setenv(HANDLER_CPU_DIR_VARIABLE, str(tmp_path / "cpu"))
    result = run_scenario(RunOptions(scenario="follow", seed=1, duration_s=2.0, processes=ProcessLayout.ONE))
    assert result.success, result.failure_reason
    services = {path.name.removesuffix(".handlers.csv").rsplit("-", 1)[-1]
                for path in (tmp_path / "cpu").glob("*.handlers.csv")}
    assert services == {"sim", "geolocation", "scene", "v2x", "planner", "control", "actuation"}
    rows = {(row.service, row.handler): row for row in read_ledgers(tmp_path / "cpu")}
    # The simulator steps 100 times in 2 s; the stack's CAN input and its control law run every step, except the
    # last steps still in flight when the run stops (lockstep lets the world lead by feedback_delay_steps).
    sim_steps = rows["sim", "timer ScenarioFeed.on_step"].calls
    assert sim_steps >= 100
    assert sim_steps - SimConfig().feedback_delay_steps <= rows["geolocation", "topic can/vehicle"].calls <= sim_steps
    assert rows["control", "timer ControlService.control"].cpu_s > 0.0
    assert all(row.cpu_s >= 0.0 for (_, handler), row in rows.items() if handler == RUNTIME_ROW)
