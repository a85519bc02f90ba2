"""The scene's V2V trust follows the v2x service's security verdicts (v2x/status): a station whose packets fail
security loses trust, and one whose signer we do not trust earns none, however well it agrees with our sensors."""

import pytest

from coopdrive.bus import Envelope
from coopdrive.services.scene.config import SceneFusionConfig, TrustConfig
from coopdrive.services.scene.fusion import SceneFusion
from coopdrive.services.scene.service import SceneService
from coopdrive.services.scene.trust import V2vTrust
from coopdrive.v1 import v2x_pb2

from .test_trust import CONFIG, feed

STATUS_PERIOD_S = 0.2
STATION = 1


def report_failures(trust: V2vTrust, end_s: float, per_status: int, untrusted: bool = False) -> None:
    failures, t = 0, 0.0
    while t < end_s - 1e-9:
        failures += per_status
        trust.on_security(STATION, failures, untrusted, t)
        t = round(t + STATUS_PERIOD_S, 9)


def test_a_station_whose_packets_keep_failing_security_falls_below_min_trusted_at_drop_per_s():
    trust = V2vTrust(CONFIG)
    report_failures(trust, 0.6, per_status=5)
    # First report credited 0.1 s, then two status periods of 0.2 s: 0.6 - 0.5 * 0.5
    assert trust.trust(STATION) == pytest.approx(0.35)
    assert not trust.trusted(STATION) and trust.state(STATION).security_failing


def test_reports_without_new_failures_cost_nothing():
    trust = V2vTrust(CONFIG)
    for t in (0.0, 0.2, 0.4):
        trust.on_security(STATION, 3, False, t)
    # only the first report brought failures (3 more than none)
    assert trust.trust(STATION) == pytest.approx(0.6 - 0.5 * 0.1)
    assert not trust.state(STATION).security_failing


def test_an_untrusted_signer_agreeing_with_our_sensors_earns_no_trust_where_a_trusted_one_does():
    trusted, untrusted = V2vTrust(CONFIG), V2vTrust(CONFIG)
    untrusted.on_security(STATION, 0, True, 0.0)
    feed(trusted, 0.0, 2.0, disagreement_m=0.2, station=STATION)
    feed(untrusted, 0.0, 2.0, disagreement_m=0.2, station=STATION)
    assert trusted.trust(STATION) == pytest.approx(0.6 + 0.05 * 2.0)
    assert untrusted.trust(STATION) == pytest.approx(0.6)


def test_an_untrusted_signer_still_loses_trust_when_it_disagrees():
    trust = V2vTrust(CONFIG)
    trust.on_security(STATION, 0, True, 0.0)
    feed(trust, 0.0, 1.0, disagreement_m=3.0, station=STATION)
    assert trust.trust(STATION) == pytest.approx(0.1)


def test_the_scene_lists_each_station_s_trust_and_security_state():
    fusion = SceneFusion(SceneFusionConfig(trust=TrustConfig()))
    fusion.trust.on_security(3002, 4, True, 1.0)
    fusion.trust.on_security(3003, 0, False, 1.0)
    scene = fusion.scene(1.0)
    by_id = {s.station_id: s for s in scene.station_trust}
    assert by_id[3002].security_failing and by_id[3002].untrusted_signer
    assert by_id[3002].trust < TrustConfig().initial
    assert by_id[3003].trusted and not by_id[3003].security_failing
    assert by_id[3003].trust == pytest.approx(TrustConfig().initial)


def test_the_scene_service_takes_the_verdicts_from_the_v2x_status():
    service = SceneService.__new__(SceneService)
    service.fusion = SceneFusion(SceneFusionConfig(trust=TrustConfig()))
    status = v2x_pb2.V2xStatus()
    status.header.sample_time_s = 2.0
    status.stations.add(station_id=3002, signed=True, messages_signed=10, messages_refused_by_security=10,
                        messages_untrusted=10, last_security_reason="unknown_issuer")
    status.stations.add(station_id=3001, signed=True, verified=True, trusted=True, messages_signed=10,
                        messages_verified=10, messages_trusted=10)
    # refused until its full certificate comes: unknown, which says nothing against it
    status.stations.add(station_id=3000, signed=True, messages_signed=5, messages_refused_by_security=5,
                        last_security_reason="unknown_signer_digest")
    status.stations.add(station_id=3021, messages_received=10)
    service.on_v2x_status(Envelope("a1", "v2x/status", status))
    stations = service.fusion.trust.stations()
    assert stations[3002].untrusted_signer and stations[3002].security_failing
    for station_id in (3001, 3000):
        assert not stations[station_id].untrusted_signer and not stations[station_id].security_failing
        assert stations[station_id].trust == pytest.approx(TrustConfig().initial)
    assert 3021 not in stations  # unsigned: security has nothing to say about it
