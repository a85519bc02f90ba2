"""Package layout: the framework lives in coopdrive/, each service in services/<name>/.

The services folder is installed as the subpackage coopdrive.services, so a wheel holds one
top-level package and nothing depends on the working directory.

The protobuf modules in coopdrive/v1/ are generated from proto/ at every install (build_py, which
an editable install runs too), so they are never checked in and never stale.
"""

import glob
import os

from setuptools import find_packages, setup
from setuptools.command.build_py import build_py

HERE = os.path.dirname(os.path.abspath(__file__))
PROTO_ROOT = os.path.join(HERE, "proto")


class BuildWithProtobuf(build_py):
    """Runs protoc (from grpcio-tools, a build requirement) on proto/coopdrive/v1 before the packages are built."""

    def run(self):
        generate_protobuf_modules(HERE)
        super().run()


def generate_protobuf_modules(out_root: str) -> None:
    from grpc_tools import protoc  # a build requirement (pyproject.toml), so imported only when building

    sources = sorted(glob.glob(os.path.join(PROTO_ROOT, "coopdrive", "v1", "*.proto")))
    if not sources:
        raise SystemExit(f"no .proto files under {PROTO_ROOT}: the protobuf modules cannot be generated")
    include = os.path.join(os.path.dirname(protoc.__file__), "_proto")
    arguments = ["protoc", f"-I{PROTO_ROOT}", f"-I{include}", f"--python_out={out_root}", f"--pyi_out={out_root}"]
    if protoc.main(arguments + sources) != 0:
        raise SystemExit("protoc failed on proto/coopdrive/v1 (its message is above)")


framework = find_packages(include=["coopdrive", "coopdrive.*"])
services = ["coopdrive.services"] + [f"coopdrive.services.{name}" for name in find_packages("services")]
data_folders = {"coopdrive.maps": "maps", "coopdrive.scenarios": "scenarios"}

setup(
    packages=framework + services + list(data_folders),
    package_dir={"coopdrive": "coopdrive", "coopdrive.services": "services", **data_folders},
    cmdclass={"build_py": BuildWithProtobuf},
)
