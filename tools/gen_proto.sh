#!/usr/bin/env bash
# Regenerate the Python protobuf modules in coopdrive/v1/ from proto/coopdrive/v1/*.proto.
# Usage: tools/gen_proto.sh [OUT_ROOT]   (default: the repository root; CI generates into a
# temporary folder and compares, so committed code never goes stale).
set -euo pipefail
here=$(cd "$(dirname "$0")/.." && pwd)
out=${1:-$here}
python=${PYTHON:-$here/.venv/bin/python}
mkdir -p "$out/coopdrive/v1"
"$python" -m grpc_tools.protoc -I"$here/proto" --python_out="$out" --pyi_out="$out" "$here"/proto/coopdrive/v1/*.proto
