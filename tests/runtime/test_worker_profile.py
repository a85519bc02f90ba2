"""COOPDRIVE_PROFILE_DIR makes every service worker write its cProfile when it stops."""

import pstats

from coopdrive.runtime.profiling import PROFILE_DIR_VARIABLE, WorkerProfile


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
