"""A sweep's fault variants (`coopdrive run all --seeds 1-20 --faults FILE`): one more dimension of the sweep.

The file is a YAML mapping from a variant's name to its list of faults, each written as in a scenario file's
`faults:` list (or `--fault`), added to the scenario's own:

    none: []                                                    # the scenarios as they are
    lossy: [{type: v2v_loss, start_s: 0, loss_probability: 0.3}]

Every scenario runs every variant on every seed. A variant's name is its folder under --out, so it is a plain
word. docs/sweep-faults.yaml is an example.
"""

from __future__ import annotations

import re
from pathlib import Path

import yaml
from pydantic import TypeAdapter, ValidationError

from coopdrive.services.sim.fault_config import Fault

# Without --faults a sweep has this one variant: no faults added.
NO_FAULTS = "none"
VARIANT_NAME = re.compile(r"[A-Za-z0-9][A-Za-z0-9_.-]*")
EXAMPLE = "lossy: [{type: v2v_loss, start_s: 0, loss_probability: 0.3}]"
_FAULT = TypeAdapter(Fault)


class FaultsFileError(ValueError):
    """A faults file that cannot be used; the message is one line naming the file and what is wrong."""


def load_fault_variants(path: Path) -> dict[str, tuple[dict, ...]]:
    """Variant name -> its faults, in the file's order; FaultsFileError names the first thing wrong."""
    try:
        data = yaml.safe_load(Path(path).read_text(encoding="utf-8"))
    except OSError as error:
        raise FaultsFileError(f"{path}: cannot read: {error.strerror or error}") from None
    except yaml.YAMLError as error:
        mark = getattr(error, "problem_mark", None)
        where = f" at line {mark.line + 1}" if mark is not None else ""
        raise FaultsFileError(f"{path}: not YAML{where}: {getattr(error, 'problem', error)}") from None
    if not isinstance(data, dict) or not data:
        raise FaultsFileError(f"{path}: a mapping of variant names to lists of faults, such as '{EXAMPLE}'")
    return {str(name): _variant(path, name, faults) for name, faults in data.items()}


def _variant(path: Path, name, faults) -> tuple[dict, ...]:
    if not isinstance(name, str) or not VARIANT_NAME.fullmatch(name):
        raise FaultsFileError(f"{path}: variant name {name!r}: letters, digits, '_', '-' and '.', "
                              "starting with a letter or digit (it names the variant's folder)")
    if not isinstance(faults, list):
        raise FaultsFileError(f"{path}: variant {name!r}: a list of faults (give [] for none)")
    for index, fault in enumerate(faults):
        where = f"{path}: variant {name!r}, fault {index}"
        if not isinstance(fault, dict):
            raise FaultsFileError(f"{where}: a mapping such as '{{type: gnss_outage, vehicle_id: ego, start_s: 5}}'")
        try:
            _FAULT.validate_python(fault)
        except ValidationError as error:
            raise FaultsFileError(f"{where}: {_first_error(error)}") from None
    return tuple(faults)


def _first_error(error: ValidationError) -> str:
    first = error.errors()[0]
    # The tagged union puts the fault's type first in the location; the rest is the key in the fault.
    keys = [str(part) for part in first["loc"][1:]]
    message = " ".join(first["msg"].split()).removeprefix("Value error, ")
    return f"{'.'.join(keys)}: {message}" if keys else message
