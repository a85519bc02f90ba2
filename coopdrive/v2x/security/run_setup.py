"""Security for a launched run: one test PKI for the stacks, and each stack's `security` v2x config section.

    overrides = security_overrides(run_dir / "pki", ["car1", "car2"], SecurityMode.VERIFY_REQUIRED,
                                   untrusted=["car2"])
    v2x_config.update(overrides["car1"])    # {"security": {"mode": ..., "pki_dir": ..., "ticket": "car1"}}

Trusted vehicles get tickets under pki_dir; untrusted ones get theirs from a second PKI under
pki_dir/untrusted whose root nobody else trusts, so the others drop their packets (unknown issuer) and treat
them as vehicles without V2V. An untrusted vehicle trusts the run's root as well, so it still hears the others.
"""

from __future__ import annotations

from collections.abc import Sequence
from pathlib import Path

from coopdrive.v2x.security.pki import create_test_pki, create_untrusted_pki
from coopdrive.v2x.security.profile import SecurityMode

UNTRUSTED_SUBDIR = "untrusted"


def security_overrides(pki_dir: Path, vehicle_ids: Sequence[str], mode: SecurityMode,
                       untrusted: Sequence[str] = (), valid_from_tai_s: int | None = None,
                       roadside_units: Sequence[str] = ()) -> dict[str, dict]:
    """Create the PKI(s) in pki_dir and return per vehicle id the `{"security": {...}}` of its v2x config.

    vehicle_ids may also name the simulator's own senders (scripted vehicles, roadside units): they get
    tickets like any vehicle and sign with them (`load_test_pki(pki_dir).signer(name)`); the roadside_units among
    them may sign SPATEMs and MAPEMs too."""
    pki_dir = Path(pki_dir)
    unknown = sorted(set(untrusted) - set(vehicle_ids))
    if unknown:
        raise ValueError(f"untrusted vehicles {unknown} are not among the run's vehicles {list(vehicle_ids)}")
    if UNTRUSTED_SUBDIR in vehicle_ids:
        raise ValueError(f"vehicle id {UNTRUSTED_SUBDIR!r} is reserved for the untrusted PKI's directory")
    trusted = [vehicle for vehicle in vehicle_ids if vehicle not in untrusted]
    create_test_pki(pki_dir, trusted, valid_from_tai_s=valid_from_tai_s, roadside_units=roadside_units)
    untrusted_dir = pki_dir / UNTRUSTED_SUBDIR
    if untrusted:
        create_untrusted_pki(untrusted_dir, list(untrusted), valid_from_tai_s=valid_from_tai_s)
    overrides = {vehicle: {"security": {"mode": mode.value, "pki_dir": str(pki_dir), "ticket": vehicle}}
                 for vehicle in trusted}
    for vehicle in untrusted:
        # Nobody trusts its tickets, but it trusts the run's root like everyone: it still hears the others.
        overrides[vehicle] = {"security": {"mode": mode.value, "pki_dir": str(untrusted_dir), "ticket": vehicle,
                                           "extra_trusted_roots": [str(pki_dir / "root.cert")],
                                           "extra_authorities": [str(pki_dir / "aa.cert")]}}
    return overrides
