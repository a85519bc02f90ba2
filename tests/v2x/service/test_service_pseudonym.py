"""Pseudonym change in the running V2xService (security.pseudonym_period_s): a new ticket, station id and MAC
together, heard and verified by another station, and held while a manoeuvre is under way."""

import pytest
from pydantic import ValidationError

from coopdrive.v2x.packet import decode_packet
from coopdrive.v2x.security.pki import load_test_pki
from coopdrive.v2x.security.verifier import SecurityVerifier
from coopdrive.services.v2x.service import V2xService
from coopdrive.v1 import ego_pb2, planner_pb2

from .test_service_security import START_S, STATIONS, deliver, overrides, station  # noqa: F401  (fixtures)
from .test_service_udp import radio, start_service  # noqa: F401  (fixtures)

PERIOD_S = 60.0
# ETSI CAM generation (the default profile) sends at the latest T_GenCamMax = 1 s after the last CAM, whatever the
# dynamics: each step below is one CAM.
CAM_PERIOD_S = 1.0


def sent(service, ctx, radio) -> bytes:  # noqa: F811
    """Our next packet: one CAM period later."""
    ctx.clock.set(ctx.now_s() + CAM_PERIOD_S)
    ctx.deliver("ego/state", ego_pb2.EgoState(x_m=5.0, y_m=2.0, heading_rad=0.2, speed_mps=15.0))
    service.transmit(ctx.now_s())
    packet, _ = radio.recvfrom(4096)
    return packet


def identity(packet: bytes, pki_dir) -> tuple[int, bytes, bytes]:
    """(station id, MAC, ticket digest) of one of our signed packets, read as a listener would."""
    opened = SecurityVerifier(load_test_pki(pki_dir).store()).unwrap(packet, count=False)
    decoded = decode_packet(opened.unsecured_packet)
    return decoded.station_id, bytes(decoded.gn.extended.source_position.address.mid), opened.result.signer_digest


def period_trigger(ctx):
    return next(trigger.handler for trigger in ctx.triggers if trigger.period_s == PERIOD_S)


def test_the_pseudonym_changes_on_its_period_and_the_new_one_is_heard_verified(station, radio, overrides):  # noqa: F811
    pki_dir = overrides["a"]["security"]["pki_dir"]
    (a, a_ctx), (b, b_ctx) = station("a", security={**overrides["a"]["security"], "pseudonym_period_s": PERIOD_S}), \
        station("b")
    before = identity(sent(a, a_ctx, radio), pki_dir)
    assert before[:2] == (STATIONS["a"][0], bytes.fromhex(STATIONS["a"][1].replace(":", "")))
    period_trigger(a_ctx)(a_ctx.now_s())
    packet = sent(a, a_ctx, radio)
    after = identity(packet, pki_dir)
    assert all(old != new for old, new in zip(before, after)), (before, after)
    assert a.counters["pseudonym_changes"] == 1
    b_ctx.clock.set(a_ctx.now_s())  # one road, one time: a packet from b's future is refused as not yet valid
    deliver(b, b_ctx, radio, packet)
    assert [cam.station_id for cam in b_ctx.messages("v2x/cam")] == [after[0]]
    [heard] = b_ctx.messages("v2x/status")[-1].stations
    assert (heard.station_id, heard.verified, heard.trusted) == (after[0], True, True)


@pytest.mark.parametrize("intent", [planner_pb2.IclcmIntent(merge_request=True),
                                    planner_pb2.IclcmIntent(forward_id=3001, backward_id=3003)],
                         ids=["merge request", "paired in a platoon"])
def test_a_change_due_during_a_manoeuvre_waits_until_it_is_over(station, radio, overrides, intent):  # noqa: F811
    pki_dir = overrides["a"]["security"]["pki_dir"]
    a, a_ctx = station("a", security={**overrides["a"]["security"], "pseudonym_period_s": PERIOD_S})
    a_ctx.deliver("planner/behaviour", planner_pb2.BehaviourRequest(iclcm=intent))
    period_trigger(a_ctx)(a_ctx.now_s())
    held = [identity(sent(a, a_ctx, radio), pki_dir)[0] for _ in range(3)]
    assert held == [STATIONS["a"][0]] * 3 and a.pseudonyms.deferred >= 3
    a_ctx.deliver("planner/behaviour", planner_pb2.BehaviourRequest())
    assert identity(sent(a, a_ctx, radio), pki_dir)[0] != STATIONS["a"][0]


def test_a_pseudonym_period_without_signing_is_refused_naming_the_key():
    with pytest.raises(ValidationError, match="security.pseudonym_period_s needs a signing security.mode"):
        V2xService.Config.model_validate({"security": {"pseudonym_period_s": 300}})
