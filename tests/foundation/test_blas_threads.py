"""Every coopdrive process loads numpy's and scipy's OpenBLAS without a pool of worker threads (coopdrive/__init__.py):
their threads spin at load and took a quarter of a second of CPU from the other core per interpreter."""

import os
import subprocess
import sys

import pytest

# What OpenBLAS reads for its thread count, in its order. An earlier test in the same worker may have set them: a
# Dask LocalCluster with worker processes sets OMP_, MKL_ and OPENBLAS_NUM_THREADS=1 in the process that starts it.
# So each check starts without any of them.
THREAD_SETTINGS = ("OPENBLAS_NUM_THREADS", "GOTO_NUM_THREADS", "OMP_NUM_THREADS")
THREAD_COUNT = "import os; print(len(os.listdir('/proc/self/task')))"
# With one usable core OpenBLAS starts no pool of its own, so there is nothing to tell apart.
needs_two_cores = pytest.mark.skipif(len(os.sched_getaffinity(0)) < 2, reason="OpenBLAS starts no pool on one core")


def threads_after_importing(first: str, environment: dict[str, str]) -> int:
    code = f"import {first}, numpy, scipy.linalg; {THREAD_COUNT}"
    result = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, env=environment,
                            check=True)
    return int(result.stdout)


def environment_without_thread_setting(**extra: str) -> dict[str, str]:
    environment = {key: value for key, value in os.environ.items() if key not in THREAD_SETTINGS}
    return {**environment, **extra}


def test_a_process_that_imports_coopdrive_first_loads_numpy_and_scipy_on_its_own_thread_alone():
    assert threads_after_importing("coopdrive", environment_without_thread_setting()) == 1


@needs_two_cores
def test_without_coopdrive_the_same_imports_start_openblas_worker_threads_so_the_check_can_fail():
    assert threads_after_importing("os", environment_without_thread_setting()) > 1


@needs_two_cores
def test_a_thread_count_the_user_sets_stands():
    assert threads_after_importing("coopdrive", environment_without_thread_setting(OPENBLAS_NUM_THREADS="2")) > 1
