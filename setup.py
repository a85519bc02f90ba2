"""Package layout: the framework lives in coopdrive/, each service in services/<name>/.

The services folder is installed as the subpackage coopdrive.services, so a wheel holds one
top-level package and nothing depends on the working directory.
"""

from setuptools import find_packages, setup

framework = find_packages(include=["coopdrive", "coopdrive.*"])
services = ["coopdrive.services"] + [f"coopdrive.services.{name}" for name in find_packages("services")]
data_folders = {"coopdrive.maps": "maps", "coopdrive.scenarios": "scenarios"}

setup(
    packages=framework + services + list(data_folders),
    package_dir={"coopdrive": "coopdrive", "coopdrive.services": "services", **data_folders},
)
