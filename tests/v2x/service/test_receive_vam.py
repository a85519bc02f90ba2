"""The v2x service hears road users: FlexStack's real VAMs (TS 103 300-3) are published on v2x/vam with their
station, position and speed, and the pedestrian's station is in the station table; thousands of mutated VAMs
(the full run, `python -m tests.v2x.service.vam_fuzz`, takes 100 000) never raise and each is accepted or counted
under a reason."""

import pytest

from coopdrive.services.v2x.plausibility import PlausibilityReason
from coopdrive.v2x.reasons import RejectReason

from .receive_fuzz import start_service
from .vam_fuzz import capture_vams, run

FLEXSTACK_VRU_STATION = 2
FLEXSTACK_VRU_POSITION_DEG = (41.387304, 2.112485)  # the capture's GN position vector of that station
PACKETS = 3000


@pytest.fixture
def service(tmp_path):
    vams = capture_vams()
    service, ctx, radio = start_service(tmp_path / "rx.pcap", vams[0][0])
    yield service, ctx, vams
    service.stop()
    radio.close()


def test_flexstacks_vams_are_published_with_their_station_position_and_speed_and_the_station_is_listed(service):
    service, ctx, vams = service
    assert len(vams) == 13
    for time_s, packet in vams:  # each heard when FlexStack sent it
        ctx.clock.set(time_s)
        service.on_datagram(packet)
        service.flush_received(ctx.now_s())
    service.publish_status(ctx.now_s())
    published = ctx.messages("v2x/vam")
    assert len(published) == 13 and {vam.station_id for vam in published} == {FLEXSTACK_VRU_STATION}
    position = published[0].reference_position
    assert (position.latitude_deg, position.longitude_deg) == pytest.approx(FLEXSTACK_VRU_POSITION_DEG)
    assert published[0].protocol_version == 3 and published[0].speed_mps == 0.0
    assert not published[0].HasField("heading_rad")  # sent as 3601, unavailable
    assert service.counters["received_vam"] == 13
    [station] = [s for s in ctx.messages("v2x/status")[-1].stations if s.station_id == FLEXSTACK_VRU_STATION]
    assert station.messages_received == 13


def test_3000_mutated_vams_pass_the_receive_path_each_accepted_or_counted_under_a_reason(tmp_path):
    outcome = run(PACKETS, tmp_path)
    assert outcome.packets == PACKETS
    assert outcome.accepted + outcome.own + outcome.beacons + sum(outcome.rejected.values()) == PACKETS
    assert set(outcome.rejected) <= {reason.value for reason in (*RejectReason, *PlausibilityReason)}
    assert outcome.accepted > 0 and outcome.received.get("received_vam", 0) == outcome.accepted
