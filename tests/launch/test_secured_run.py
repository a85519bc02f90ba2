"""`coopdrive run SCENARIO --security MODE [--untrusted VEHICLE]`: the specs a secured run starts with."""

import pytest
from pydantic import ValidationError

from coopdrive.launch.run import RunOptions, build_specs
from coopdrive.launch.run_spec import RunSpec
from coopdrive.launch.scenario_source import resolve_scenario
from coopdrive.services.sim.scenario_config import ScenarioError
from coopdrive.v2x.security.pki import load_test_pki
from coopdrive.v2x.timebase import tai_ms_from_utc


def specs_of(tmp_path, **options):
    specs = build_specs(RunOptions(scenario="merge", stacks=2, **options), tmp_path)
    return {(spec.vehicle_id, spec.service): spec.config for spec in specs}


def test_every_stack_verifies_with_its_own_ticket_and_the_simulator_signs_its_senders(tmp_path):
    specs = specs_of(tmp_path, security="verify_required")
    for vehicle in ("a1", "a2"):
        assert specs[(vehicle, "v2x")]["security"] == {"mode": "verify_required", "pki_dir": str(tmp_path / "pki"),
                                                      "ticket": vehicle}
    assert specs[("world", "sim")]["security_pki_dir"] == str(tmp_path / "pki")
    tickets = load_test_pki(tmp_path / "pki").tickets
    assert {"a1", "a2", "rsu", "traffic", "b1"} <= set(tickets)


def test_an_untrusted_stack_gets_its_ticket_from_a_root_nobody_else_trusts(tmp_path):
    specs = specs_of(tmp_path, security="verify_required", untrusted=("a2",))
    assert specs[("a2", "v2x")]["security"]["pki_dir"] == str(tmp_path / "pki" / "untrusted")
    assert load_test_pki(tmp_path / "pki" / "untrusted").root != load_test_pki(tmp_path / "pki").root


def test_an_unsecured_run_has_no_pki(tmp_path):
    specs = specs_of(tmp_path)
    assert "security" not in specs[("a1", "v2x")] and not specs[("world", "sim")]["security_pki_dir"]
    assert not (tmp_path / "pki").exists()


def test_an_unknown_security_mode_is_refused_where_the_run_is_described_naming_the_field():
    with pytest.raises(ValidationError, match="security"):
        RunSpec(security="paranoid")


def test_a_stack_vehicle_the_run_lacks_is_refused_as_untrusted_naming_it(tmp_path):
    with pytest.raises(ScenarioError, match="--untrusted b3: not a stack vehicle"):
        specs_of(tmp_path, security="verify_required", untrusted=("b3",))


def test_follow_is_a_scenario_file_like_any_other_so_its_stack_runs_v2x_with_security(tmp_path):
    specs = build_specs(RunOptions(scenario="follow", security="sign_only"), tmp_path)
    [v2x] = [spec for spec in specs if spec.service == "v2x"]
    assert v2x.vehicle_id == "ego" and v2x.config["security"]["mode"] == "sign_only"



EXPIRY_S = 3.0


def test_a_ticket_expired_fault_gives_the_vehicle_tickets_that_end_at_the_fault_s_start(tmp_path):
    fault = {"type": "ticket_expired", "vehicle_id": "a1", "start_s": EXPIRY_S}
    specs_of(tmp_path, security="verify_required", untrusted=("a2",), extra_faults=(fault,))
    epoch_tai_s = tai_ms_from_utc(resolve_scenario("merge").config.utc_epoch) // 1000
    trusted, untrusted = load_test_pki(tmp_path / "pki"), load_test_pki(tmp_path / "pki" / "untrusted")
    assert len(trusted.tickets["a1"]) == 3
    for ticket, _ in trusted.tickets["a1"]:
        assert ticket.valid_until_s == epoch_tai_s + EXPIRY_S and ticket.valid_from_s < epoch_tai_s
    # the others keep tickets valid for days; the untrusted stack's PKI is left as it was
    assert all(ticket.valid_until_s > epoch_tai_s + 3600 for ticket, _ in trusted.tickets["b1"])
    assert all(ticket.valid_until_s > epoch_tai_s + 3600 for ticket, _ in untrusted.tickets["a2"])


def test_a_ticket_expired_fault_without_security_is_refused(tmp_path):
    with pytest.raises(ScenarioError, match="ticket_expired needs --security"):
        specs_of(tmp_path, extra_faults=({"type": "ticket_expired", "vehicle_id": "a1", "start_s": 1.0},))
