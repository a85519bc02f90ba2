import hashlib
import stat

from coopdrive.v2x.security.certificate import Certificate
from coopdrive.v2x.security.crypto import Curve, curve_of_key
from coopdrive.v2x.security.pki import load_test_pki, pki_init
from coopdrive.v2x.security.profile import TICKET_PSIDS
from coopdrive.v2x.security.verifier import SecurityVerifier

from .signed import cam_packet, now_tai_us


def test_pki_init_writes_a_root_an_authority_and_tickets_that_load_back_and_sign(tmp_path, capsys):
    assert pki_init(tmp_path, ["ego", "lead"]) == 0
    names = sorted(str(path.relative_to(tmp_path)) for path in tmp_path.rglob("*") if path.is_file())
    assert names[:4] == ["aa.cert", "aa.key.pem", "root.cert", "root.key.pem"]
    assert "vehicles/lead/ticket-2.cert" in names and "vehicles/ego/ticket-0.key.pem" in names
    assert stat.S_IMODE((tmp_path / "root.key.pem").stat().st_mode) == 0o600
    pki = load_test_pki(tmp_path)
    assert pki.root.is_self_signed and pki.authority.issuer_digest == pki.root.digest
    ticket, key = pki.tickets["ego"][0]
    assert ticket.issuer_digest == pki.authority.digest and ticket.app_psids == set(TICKET_PSIDS)
    assert curve_of_key(key) is Curve.NIST_P256
    signer, now = pki.signer("ego"), now_tai_us()
    assert SecurityVerifier(pki.store()).verify(signer.sign(cam_packet(signer), now), now).ok
    assert pki.root.digest.hex() in capsys.readouterr().out


def test_a_written_certificate_is_canonical_oer_named_by_the_last_8_bytes_of_its_sha256(tmp_path):

    pki_init(tmp_path, ["ego"])
    encoded = (tmp_path / "vehicles/ego/ticket-0.cert").read_bytes()
    certificate = Certificate.from_bytes(encoded)
    assert certificate.encoded == encoded and certificate.digest == hashlib.sha256(encoded).digest()[-8:]


def test_pki_init_refuses_to_overwrite_an_existing_pki(tmp_path, capsys):
    assert pki_init(tmp_path, ["ego"]) == 0
    root = (tmp_path / "root.cert").read_bytes()
    assert pki_init(tmp_path, ["ego"]) == 1
    assert (tmp_path / "root.cert").read_bytes() == root and "not overwriting" in capsys.readouterr().err
