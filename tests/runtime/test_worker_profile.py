"""COOPDRIVE_PROFILE_DIR makes every service worker write its cProfile when it stops; COOPDRIVE_PROFILE_CLOCK=cpu
times it on the thread's CPU clock."""

import pstats
import time

from coopdrive.runtime.profiling import PROFILE_CLOCK_VARIABLE, PROFILE_DIR_VARIABLE, WorkerProfile

WAIT_S = 0.2


def busy() -> int:
    return sum(k * k for k in range(10_000))


def test_a_worker_writes_its_profile_where_the_environment_says(tmp_path, monkeypatch):
    monkeypatch.setenv(PROFILE_DIR_VARIABLE, str(tmp_path / "profiles"))
    with WorkerProfile.from_environment("ego-scene"):
        busy()
    stats = pstats.Stats(str(tmp_path / "profiles" / "ego-scene.prof"))
    assert any(name == "busy" for (_, _, name) in stats.stats)


def test_without_the_variable_nothing_is_profiled_or_written(tmp_path, monkeypatch):
    monkeypatch.delenv(PROFILE_DIR_VARIABLE, raising=False)
    monkeypatch.chdir(tmp_path)
    with WorkerProfile.from_environment("ego-scene"):
        busy()
    assert list(tmp_path.iterdir()) == []


def profiled_seconds_of(function_name: str, tmp_path, monkeypatch, clock: str, work) -> float:
    monkeypatch.setenv(PROFILE_DIR_VARIABLE, str(tmp_path / clock))
    monkeypatch.setenv(PROFILE_CLOCK_VARIABLE, clock)
    with WorkerProfile.from_environment("ego-group"):
        work()
    stats = pstats.Stats(str(tmp_path / clock / "ego-group.prof"))
    return next(timing[3] for (_, _, name), timing in stats.stats.items() if name == function_name)


def wait_for_a_queue() -> None:
    time.sleep(WAIT_S)


def test_on_the_cpu_clock_a_wait_costs_nothing_and_on_the_wall_clock_it_costs_its_length(tmp_path, monkeypatch):
    cpu_s = profiled_seconds_of("wait_for_a_queue", tmp_path, monkeypatch, "cpu", wait_for_a_queue)
    wall_s = profiled_seconds_of("wait_for_a_queue", tmp_path, monkeypatch, "wall", wait_for_a_queue)
    assert cpu_s < WAIT_S / 10
    assert wall_s >= WAIT_S


def test_an_unknown_clock_is_named_in_a_warning_and_the_wall_clock_is_used(tmp_path, monkeypatch, caplog):
    wall_s = profiled_seconds_of("wait_for_a_queue", tmp_path, monkeypatch, "cycles", wait_for_a_queue)
    assert wall_s >= WAIT_S
    assert "COOPDRIVE_PROFILE_CLOCK='cycles' is none of wall, cpu" in caplog.text
