"""An independent check of our reading of TS 103 097 v1.2.1: the version-2 certificates of the FOKUS WebValidator
(a root CA, two authorisation authorities and an authorisation ticket, published in Vanetza's unit tests,
vanetza/security/v2/tests/certificate.cpp) parse, each names its issuer by the HashedId8 we compute for the
issuer's certificate, and each signature verifies with the issuer's key: length coding, certificate layout, the
canonical digest (clause 4.2.12) and the signature convention are those of another implementation.

The bytes are not copied here: set COOPDRIVE_VANETZA_DIR to a Vanetza checkout (github.com/riebl/vanetza)."""

import os
import re
from pathlib import Path

import pytest

from coopdrive.v2x.security.v121_certificate import read_certificate, verify_ecdsa
from coopdrive.v2x.security.v121_message import parse_secured_message
from coopdrive.v2x.security.v121_reader import PayloadType, PresentationReader

VANETZA_DIR = os.environ.get("COOPDRIVE_VANETZA_DIR")
CERTIFICATES = "vanetza/security/v2/tests/certificate.cpp"
# SecuredMessages that Vanetza adapted from the WebValidator's version 1 (so their signatures no longer verify).
MESSAGES = "vanetza/security/v2/tests/secured_message.cpp"
MESSAGE_ITS_AID = 2
ROOT, TICKET = 4, 1  # SubjectType
# TEST(Certificate, NAME) { const char str[] = "HEX" "HEX" ...;
_TEST = re.compile(r'TEST\(\w+, (\w+)\)\s*\{[^}]*?char str\[\] =\s*((?:"[0-9A-Fa-f]+"\s*)+);')

pytestmark = pytest.mark.skipif(VANETZA_DIR is None, reason="COOPDRIVE_VANETZA_DIR (a Vanetza checkout) not set")


def published(path: str) -> dict:
    source = (Path(VANETZA_DIR) / path).read_text()
    return {match.group(1): bytes.fromhex("".join(re.findall(r'"([0-9A-Fa-f]+)"', match.group(2))))
            for match in _TEST.finditer(source)}


def test_the_published_v121_certificate_chain_parses_names_its_issuers_by_our_digest_and_verifies():
    certificates = {}
    for name, encoded in published(CERTIFICATES).items():
        reader = PresentationReader(encoded)
        certificates[name] = read_certificate(reader)
        assert reader.at_end, name
    by_digest = {certificate.digest: certificate for certificate in certificates.values()}
    assert {certificate.subject_type for certificate in certificates.values()} >= {ROOT, TICKET}
    for name, certificate in certificates.items():
        issuer = certificate if certificate.issuer_digest is None else by_digest[certificate.issuer_digest]
        assert verify_ecdsa(issuer.public_key, certificate.signature, certificate.signed_bytes), name


def test_the_published_v121_secured_messages_parse_to_their_signer_its_aid_payload_and_signature():
    messages = published(MESSAGES)
    assert messages
    for name, encoded in messages.items():
        message = parse_secured_message(encoded)
        assert (message.signer, message.psid, message.payload_type) == ("certificate", MESSAGE_ITS_AID,
                                                                         PayloadType.SIGNED), name
        assert message.signature is not None and message.generation_time_us is not None, name
