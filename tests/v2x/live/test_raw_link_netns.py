"""Two of our v2x services on the raw link across real interfaces, one in each network namespace of a veth pair:
each hears the other's CAMs. Independent of any peer stack, it shows the raw link carries our GN frames between
machines-to-be as it will between two vehicles' OCB interfaces."""

import pytest

from tests.system_packages import needs
from tests.v2x.live.exchange import run_exchange
from tests.v2x.live.netns import VethPair
from tests.v2x.live.stations import SPEED_MPS, our_config, our_station, ours_ran

pytestmark = [pytest.mark.whole_run, needs("ip")]

STATIONS = {"a": (2001, "02:00:00:00:20:01"), "b": (2002, "02:00:00:00:20:02")}


@pytest.fixture(scope="module")
def summaries(tmp_path_factory):
    folder = tmp_path_factory.mktemp("raw_netns")
    with VethPair.create() as pair:
        ends = {"a": pair.a, "b": pair.b}
        stations = {}
        for name, (station_id, mac) in STATIONS.items():
            config = our_config(folder, ends[name].interface, station_id, mac)
            stations[name] = pair.command(ends[name], *our_station(config))
        summaries = run_exchange(stations, folder)
    return {name: ours_ran(summary) for name, summary in summaries.items()}


@pytest.mark.parametrize("listener, speaker", [("a", "b"), ("b", "a")])
def test_each_of_our_services_hears_the_others_cams_across_the_veth_pair(summaries, listener, speaker):
    station_id = STATIONS[speaker][0]
    heard = summaries[listener]["cams"][str(station_id)]
    assert heard["count"] > 0 and heard["speed_mps"] == pytest.approx(SPEED_MPS)
    stations = summaries[listener]["status"]["stations"]
    assert [s["station_id"] for s in stations] == [station_id]
    # Nothing on the wire was refused for what it is: only the two stations' GN frames cross it. A CAM older than the
    # plausibility check's 1 s when its service read it is the host's lag, not the link's (one CAM, in a full
    # suite beside two others), so those are only bounded.
    rejected = dict(summaries[listener]["status"].get("rejected_by_reason", {}))
    too_old = int(rejected.pop("too_old", 0))
    assert rejected == {}
    assert too_old <= heard["count"] // 10
