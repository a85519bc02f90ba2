"""A station's iCLCM acceleration request lands on its scene object while fresh and while the station is trusted."""

import pytest

from coopdrive.services.scene.intended_accel import IntendedAccelerations
from coopdrive.v1 import header_pb2, its_pb2, scene_pb2

MAX_AGE_S = 0.4
MIN_TRUST = 0.4


def iclcm(station_id: int, accel_mps2: float | None) -> its_pb2.IclcmContent:
    content = its_pb2.IclcmContent(station_id=station_id)
    if accel_mps2 is not None:
        content.target_longitudinal_acceleration_mps2 = accel_mps2
    return content


def scene_with(station_id: int, link_confidence: float = 0.9, trust: float = 0.8) -> scene_pb2.Scene:
    scene = scene_pb2.Scene()
    obj = scene.objects.add(object_id=3, v2v_trust=trust)
    obj.station_id.value, obj.station_id.confidence = station_id, link_confidence
    return scene


def annotated(requests: IntendedAccelerations, scene: scene_pb2.Scene, now_s: float) -> scene_pb2.ScalarProperty:
    requests.annotate(scene, now_s)
    return scene.objects[0].intended_accel_mps2


def test_a_fresh_request_of_a_trusted_linked_station_is_put_on_its_object():
    requests = IntendedAccelerations(MAX_AGE_S, MIN_TRUST)
    requests.on_iclcm(iclcm(2002, -5.5), 10.0)
    intended = annotated(requests, scene_with(2002), 10.1)
    assert intended.value == pytest.approx(-5.5)
    assert list(intended.sources) == [header_pb2.SENSOR_SOURCE_V2V]
    assert intended.valid_until_s == pytest.approx(10.4)


@pytest.mark.parametrize("scene, now_s", [
    (scene_with(2002), 10.5),
    (scene_with(2002, trust=0.2), 10.1),
    (scene_with(2002, link_confidence=0.0), 10.1),
    (scene_with(2099), 10.1),
], ids=["older than 400 ms", "untrusted station", "object not linked", "another station"])
def test_a_request_is_left_off_when_it_says_nothing_reliable_about_this_object_now(scene, now_s):
    requests = IntendedAccelerations(MAX_AGE_S, MIN_TRUST)
    requests.on_iclcm(iclcm(2002, -5.5), 10.0)
    assert not annotated(requests, scene, now_s).sources


def test_an_iclcm_without_a_request_or_arriving_late_does_not_replace_the_latest():
    requests = IntendedAccelerations(MAX_AGE_S, MIN_TRUST)
    requests.on_iclcm(iclcm(2002, -1.0), 10.0)
    requests.on_iclcm(iclcm(2002, None), 10.04)
    requests.on_iclcm(iclcm(2002, 0.5), 9.96)
    assert annotated(requests, scene_with(2002), 10.1).value == pytest.approx(-1.0)
