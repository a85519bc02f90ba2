"""tools/v2x_live_peer.sh: the live exchange at a desk, here on a veth pair standing in for two OCB cards of one
machine (both ends in one namespace), and its one line when the interface is missing."""

import subprocess

import pytest

from tests.system_packages import needs
from tests.v2x.live.netns import VethPair
from tests.v2x.live.stations import ROOT, needs_peer_env

pytestmark = [pytest.mark.whole_run, needs("ip")]

TOOL = ROOT / "tools" / "v2x_live_peer.sh"
RUN_TIMEOUT_S = 300.0
DURATION_S = "6"


def run_tool(pair: VethPair, *args: str) -> subprocess.CompletedProcess:
    return subprocess.run(pair.command(pair.a, str(TOOL), "--duration-s", DURATION_S, *args), capture_output=True,
                          text=True, timeout=RUN_TIMEOUT_S, cwd=ROOT)


def test_the_desk_tool_says_what_our_station_and_flexstack_heard_of_each_other():
    needs_peer_env()
    with VethPair.create(together=True) as pair:
        result = run_tool(pair, "--interface", pair.a.interface, "--flexstack-interface", pair.b.interface)
    assert result.returncode == 0, result.stderr
    lines = result.stdout.splitlines()
    assert any(line.startswith("ours: CAMs from 4242: ") for line in lines), result.stdout
    assert any(line.startswith("flexstack: CAMs from 1001: ") for line in lines), result.stdout
    assert any(line.startswith("flexstack: DENMs from 1001: ") for line in lines), result.stdout


def test_the_desk_tool_on_a_missing_interface_ends_with_the_services_one_line():
    with VethPair.create() as pair:
        result = run_tool(pair, "--interface", "ocb9")
    assert result.returncode == 1
    assert result.stderr.splitlines()[-1] == ("v2x live: our service stopped: coopdrive: v2x raw link: no network "
                                              "interface 'ocb9' (see `ip link`)")
