"""The topic registry is built from each service's own declaration (services/<name>/topics.py), and the topics on
the wire stay what recordings and other stacks expect."""

import pytest

from coopdrive.bus import TOPICS
from coopdrive.bus.services import SERVICES, VEHICLE_STACK, service_entry
from coopdrive.bus.topic import EVERY_OTHER_TOPIC, Topic
from coopdrive.bus.topics import declarations_of, published_by, topic_registry
from coopdrive.runtime.registry import service_class
from coopdrive.runtime.testing import MemoryContext

# Every topic on the wire and its message, by publisher: a renamed key or a changed type breaks recordings and
# mixed-version stacks, so a change here must be meant.
WIRE = {
    "sim": {"clock": "SimClock", "ground_truth": "GroundTruth", "result": "RunResult", "service_fault": "ServiceFault",
            "gnss/fix": "GnssFix", "gnss/serial_mark": "WireMark", "radio/mark": "WireMark",
            "can/vehicle": "CanFrames", "lidar/scan": "LidarScan", "camera/frame": "CameraFrame",
            "sonar/ranges": "SonarRanges"},
    "geolocation": {"ego/state": "EgoState", "ego/gnss": "GnssFix", "gnss/nmea": "NmeaChunk"},
    "v2x": {"v2x/rx": "GnPacket", "v2x/tx": "GnPacket", "v2x/status": "V2xStatus", "v2x/cam": "CamContent",
            "v2x/denm": "DenmContent", "v2x/iclcm": "IclcmContent", "v2x/spatem": "SpatemContent",
            "v2x/mapem": "MapemContent", "v2x/srem": "SremContent", "v2x/ssem": "SsemContent",
            "v2x/vam": "VamContent"},
    "scene": {"scene": "Scene"},
    "planner": {"planner/state": "PlannerState", "planner/behaviour": "BehaviourRequest",
                "planner/lights": "PlannerState"},
    "control": {"control/command": "ControlCommand"},
    "actuation": {"can/command": "CanFrame", "actuation/command": "ActuatorCommand",
                  "actuation/status": "ActuationStatus", "actuation/override": "OverrideEvent"},
    "gateway": {"gateway/mode_request": "ModeRequest", "gateway/estop": "EmergencyStop",
                "gateway/planner_force": "PlannerForce"},
}
# Only observed: nobody waits for them in lockstep.
UNSTEPPED = {"service_fault"} | {f"diagnostics/{service}" for service in WIRE}
# Subscriptions a service makes only on hardware or in a lockstep run paced by the simulator's marks, so a service
# started on a MemoryContext (as under replay) does not make them.
LIVE_ONLY_SUBSCRIPTIONS = {"geolocation": {"gnss/serial_mark"}, "v2x": {"radio/mark"}}


def test_the_registry_carries_the_same_topics_and_messages_as_the_wire():
    on_wire = {name: (f"coopdrive.v1.{message}", publisher)
               for publisher, topics in WIRE.items() for name, message in topics.items()}
    on_wire |= {f"diagnostics/{service}": ("coopdrive.v1.Diagnostics", service) for service in WIRE}
    assert {name: (topic.type_name, topic.publisher) for name, topic in TOPICS.items()} == on_wire
    assert {name for name, topic in TOPICS.items() if not topic.stepped} == UNSTEPPED


def test_every_service_in_the_table_declares_its_own_topics():
    for entry in SERVICES:
        assert {topic.name for topic in published_by(entry)} == set(WIRE[entry.name])


def test_a_declaration_of_another_services_topic_is_refused(monkeypatch):
    scene = service_entry("scene")
    stray = Topic("control/command", TOPICS["control/command"].message_type, "control")
    monkeypatch.setattr(declarations_of(scene), "PUBLISHES", (stray,))
    with pytest.raises(ValueError, match="another publisher: control/command"):
        published_by(scene)


def test_every_declared_subscription_names_a_published_topic():
    for entry in SERVICES:
        unknown = set(declarations_of(entry).SUBSCRIBES) - set(topic_registry()) - {EVERY_OTHER_TOPIC}
        assert unknown == set(), entry.name


@pytest.mark.parametrize("name", VEHICLE_STACK)
def test_a_stack_service_subscribes_to_what_it_declares(name):
    cls = service_class(name)
    ctx = MemoryContext(service_name=name)
    service = cls(cls.Config(), ctx)
    service.start()
    try:
        subscribed = {topic for _, topic in ctx.subscriptions()}
    finally:
        service.stop()
    declared = set(declarations_of(service_entry(name)).SUBSCRIBES)
    assert subscribed == declared - LIVE_ONLY_SUBSCRIPTIONS.get(name, set())
