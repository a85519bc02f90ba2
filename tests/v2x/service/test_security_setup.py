"""Every bad security setting of the v2x service (root, authority, ticket, key file) is one line naming the setting,
the file and the reason, and the service does not start."""

import shutil

import pytest

from coopdrive.services.v2x.config import SecurityConfig
from coopdrive.v2x.security.pki import create_test_pki
from coopdrive.services.v2x.security_setup import SecuritySettingError, load_security_material


@pytest.fixture(scope="module")
def pki_template(tmp_path_factory):
    directory = tmp_path_factory.mktemp("pki")
    create_test_pki(directory, ["ego"], tickets_per_vehicle=2)
    other = tmp_path_factory.mktemp("other-pki")
    create_test_pki(other, ["stranger"], tickets_per_vehicle=1)
    return directory, other


@pytest.fixture
def pki(pki_template, tmp_path):
    mine, other = pki_template
    shutil.copytree(mine, tmp_path / "pki")
    shutil.copytree(other, tmp_path / "other")
    return tmp_path / "pki", tmp_path / "other"


def flip_last_byte(path):
    data = bytearray(path.read_bytes())
    data[-1] ^= 0xFF
    path.write_bytes(bytes(data))


def refused(**settings) -> str:
    with pytest.raises(SecuritySettingError) as raised:
        load_security_material(SecurityConfig.model_validate(settings))
    message = str(raised.value)
    assert "\n" not in message
    return message


def test_a_good_pki_loads_its_root_authority_and_both_tickets_with_their_keys(pki):
    mine, other = pki
    material = load_security_material(SecurityConfig(mode="sign_and_verify", pki_dir=mine, ticket="ego",
                                                     extra_trusted_roots=[other / "root.cert"],
                                                     extra_authorities=[other / "aa.cert"]))
    assert [root.name for root in material.roots] == ["root", "root"]
    assert len(material.authorities) == 2 and len(material.tickets) == 2


def test_an_extra_trusted_root_whose_self_signature_does_not_verify_is_named(pki):
    mine, other = pki
    flip_last_byte(other / "root.cert")
    message = refused(mode="sign_and_verify", pki_dir=mine, ticket="ego", extra_trusted_roots=[other / "root.cert"])
    assert message == f"security.extra_trusted_roots {other / 'root.cert'}: root's self-signature does not verify"


def test_an_extra_trusted_root_that_is_no_certificate_is_named(pki, tmp_path):
    mine, _ = pki
    (tmp_path / "junk.cert").write_bytes(b"not a certificate")
    assert refused(mode="sign_and_verify", pki_dir=mine, ticket="ego", extra_trusted_roots=[tmp_path / "junk.cert"]).startswith(
        f"security.extra_trusted_roots {tmp_path / 'junk.cert'}: not a COER certificate (invalid_certificate")


def test_the_pki_s_own_root_and_authority_are_checked_too(pki):
    mine, _ = pki
    flip_last_byte(mine / "aa.cert")
    assert refused(mode="sign_and_verify", pki_dir=mine, ticket="ego") == \
        f"security.pki_dir {mine / 'aa.cert'}: aa's signature by root does not verify"


def test_an_extra_authority_issued_by_a_root_nobody_configured_is_known_but_chains_to_nothing_trusted(pki):
    mine, other = pki
    material = load_security_material(SecurityConfig(mode="sign_and_verify", pki_dir=mine, ticket="ego",
                                                     extra_authorities=[other / "aa.cert"]))
    assert len(material.authorities) == 2 and len(material.roots) == 1


def test_an_extra_authority_whose_signature_its_configured_root_did_not_make_is_named(pki):
    mine, other = pki
    flip_last_byte(other / "aa.cert")
    assert refused(mode="sign_and_verify", pki_dir=mine, ticket="ego", extra_trusted_roots=[other / "root.cert"],
                   extra_authorities=[other / "aa.cert"]) == \
        f"security.extra_authorities {other / 'aa.cert'}: aa's signature by root does not verify"


def test_a_ticket_that_is_no_certificate_is_named(pki):
    mine, _ = pki
    ticket = mine / "vehicles" / "ego" / "ticket-1.cert"
    ticket.write_bytes(b"xx")
    assert refused(mode="sign_and_verify", pki_dir=mine, ticket="ego").startswith(
        f"security.ticket {ticket}: not a COER certificate")


def test_a_missing_a_garbled_and_a_wrong_key_file_are_each_named(pki):
    mine, _ = pki
    folder = mine / "vehicles" / "ego"
    key = folder / "ticket-0.key.pem"
    key.write_text("-----BEGIN PRIVATE KEY-----\nAAAA\n-----END PRIVATE KEY-----\n")
    assert refused(mode="sign_and_verify", pki_dir=mine, ticket="ego") == \
        f"security.ticket {key}: not an EC private key in PEM (Could not deserialize key data)"
    shutil.copy(folder / "ticket-1.key.pem", key)
    assert refused(mode="sign_and_verify", pki_dir=mine, ticket="ego") == \
        f"security.ticket {key}: not the key of ticket-0.cert"
    key.unlink()
    assert refused(mode="sign_and_verify", pki_dir=mine, ticket="ego") == \
        f"security.ticket {key}: cannot be read (No such file or directory)"


def test_the_service_with_a_corrupt_extra_trusted_root_exits_non_zero_with_one_line_naming_the_file(
        pki, spawn, endpoint, tmp_path):
    mine, other = pki
    flip_last_byte(other / "root.cert")
    config = tmp_path / "v2x.yaml"
    config.write_text(f"security: {{mode: sign_and_verify, pki_dir: {mine}, ticket: ego, "
                      f"extra_trusted_roots: [{other / 'root.cert'}]}}\n")
    process = spawn("service", "v2x", "--config", str(config), "--vehicle", "ego", "--connect", endpoint)
    _, stderr = process.communicate(timeout=60)
    assert process.returncode != 0
    assert stderr.strip() == (f"coopdrive: security.extra_trusted_roots {other / 'root.cert'}: root's "
                              "self-signature does not verify")
