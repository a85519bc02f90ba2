"""The launcher starts a run's processes without loading what they load: the services' code (filterpy, scipy's
statistics, the simulator) is imported by the processes that run it, in parallel, not first by the launcher."""

import json
import subprocess
import sys

LOADED_BY_THE_SERVICES = ("filterpy", "scipy.stats", "coopdrive.services.sim.scenario_feed",
                          "coopdrive.services.geolocation.service", "coopdrive.services.scene.service",
                          "coopdrive.recording.writer", "coopdrive.visual", "cryptography")


def modules_after(statement: str) -> set[str]:
    code = f"import json, sys\n{statement}\nprint(json.dumps(sorted(sys.modules)))"
    output = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, check=True).stdout
    return set(json.loads(output))


def test_the_launcher_and_its_command_line_load_none_of_the_services_code():
    loaded = modules_after("import coopdrive.cli, coopdrive.launch.run")
    assert not [name for name in LOADED_BY_THE_SERVICES if name in loaded]


def test_building_a_runs_specs_loads_none_of_the_services_code():
    loaded = modules_after("from coopdrive.launch.run import RunOptions, build_specs\n"
                           "build_specs(RunOptions(scenario='follow'))")
    assert not [name for name in LOADED_BY_THE_SERVICES if name in loaded]
