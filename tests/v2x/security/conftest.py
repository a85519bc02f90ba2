import pytest

from coopdrive.v2x.security.crypto import Curve
from coopdrive.v2x.security.pki import create_test_pki


@pytest.fixture(scope="module", params=list(Curve), ids=lambda curve: curve.name.lower())
def pki(request, tmp_path_factory):
    """A test PKI (root -> authority -> tickets for vehicles a and b) on each allowed curve."""
    return create_test_pki(tmp_path_factory.mktemp("pki"), ["a", "b"], request.param)


@pytest.fixture(scope="module")
def p256_pki(tmp_path_factory):
    return create_test_pki(tmp_path_factory.mktemp("pki"), ["a", "b"], Curve.NIST_P256)
