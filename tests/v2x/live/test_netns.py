"""The wire of the live tests: two namespaces and a veth pair, made and always removed; a machine where namespaces
cannot be made skips the live tests naming ip's own error."""

import subprocess

import pytest

from tests.system_packages import needs, require
from tests.v2x.live import netns
from tests.v2x.live.netns import NamespaceError, VethPair

pytestmark = needs("ip")


def namespaces() -> str:
    return subprocess.run([require("ip"), "netns", "list"], capture_output=True, text=True, check=True).stdout


def test_the_pair_is_up_in_two_namespaces_and_gone_with_them_after_the_block():
    with VethPair.create() as pair:
        link = subprocess.run(pair.command(pair.a, require("ip"), "link", "show", pair.a.interface),
                              capture_output=True, text=True, check=True).stdout
        assert "state UP" in link and pair.a.namespace in namespaces() and pair.b.namespace in namespaces()
    assert pair.a.namespace not in namespaces() and pair.b.namespace not in namespaces()


def test_where_namespaces_cannot_be_made_the_test_skips_with_ips_error_line(monkeypatch):
    def refused(*args):
        raise NamespaceError(f"`ip {' '.join(args)}`: mount --make-shared /run/netns failed: Operation not permitted")

    monkeypatch.setattr(netns, "_ip", refused)
    with pytest.raises(pytest.skip.Exception, match="network namespaces cannot be made here: .*Operation not perm"):
        VethPair.create()
