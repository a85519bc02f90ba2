"""The simulator's own senders sign with the run's test PKI, and a stack of that run verifies them at the
scenario's clock (2016), while a stack trusting another root refuses them."""

import datetime as dt

import pytest

from coopdrive.roadmap import RoadMap
from coopdrive.services.sim.intent_encoder import IntentEncoder
from coopdrive.services.sim.participants import IntentKind, MessageIntent
from coopdrive.services.sim.sender_signing import SenderSigning
from coopdrive.v2x.security.pki import create_test_pki
from coopdrive.v2x.security.store import CertificateStore
from coopdrive.v2x.security.verifier import SecurityVerifier
from coopdrive.v2x.timebase import ItsClock, tai_ms_from_utc

EPOCH = dt.datetime(2016, 5, 28, 10, 0, tzinfo=dt.timezone.utc)
VALID_FROM_TAI_S = tai_ms_from_utc(EPOCH) // 1000 - 3600
ROADWORKS = {"cause_code": 3, "x_m": 1477.0, "y_m": 260.0, "closed_lane": 1, "since_s": 10.0}


@pytest.fixture(scope="module")
def signed_denm(tmp_path_factory):
    pki_dir = tmp_path_factory.mktemp("pki")
    pki = create_test_pki(pki_dir, ["rsu"], valid_from_tai_s=VALID_FROM_TAI_S)
    intent = MessageIntent(IntentKind.DENM, "rsu", 3000, 12.0, ROADWORKS)
    packet = IntentEncoder(RoadMap.load("a270").to_geodetic, EPOCH).encode(intent)
    return pki, SenderSigning(pki_dir, EPOCH).seal(intent, packet)


def now_tai_us(clock_s):
    return ItsClock(EPOCH.timestamp()).tai_ms(clock_s) * 1000


def test_a_roadside_unit_denm_signed_in_the_run_verifies_at_the_scenario_clock(signed_denm):
    pki, packet = signed_denm
    opened = SecurityVerifier(pki.store()).open(packet, now_tai_us(12.05))
    assert opened.result.ok and opened.verified and opened.full_certificate


def test_a_stack_trusting_another_root_refuses_the_signed_denm(signed_denm, tmp_path):
    _, packet = signed_denm
    stranger = create_test_pki(tmp_path, valid_from_tai_s=VALID_FROM_TAI_S)
    verifier = SecurityVerifier(CertificateStore(trusted_roots=[stranger.root], authorities=[stranger.authority]))
    assert not verifier.open(packet, now_tai_us(12.05)).result.ok


def test_a_sender_without_a_ticket_is_named(tmp_path):
    create_test_pki(tmp_path, ["rsu"], valid_from_tai_s=VALID_FROM_TAI_S)
    intent = MessageIntent(IntentKind.CAM, "traffic", 3021, 1.0, {})
    with pytest.raises(KeyError, match="no ticket for sender 'traffic'"):
        SenderSigning(tmp_path, EPOCH).seal(intent, b"")
