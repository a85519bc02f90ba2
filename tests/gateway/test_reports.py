"""Health and state reports built from a store snapshot: status rules and vehicle-clock ages."""

from coopdrive.services.gateway.models import HealthStatus, ServiceStatus
from coopdrive.services.gateway.reports import health_report, state_report
from coopdrive.services.gateway.state_store import StateStore
from coopdrive.v1 import ego_pb2, scene_pb2

TOPICS = {"sim": ["clock"], "geolocation": ["ego/state"], "scene": ["scene"]}
REQUIRED = ["sim", "geolocation", "scene"]
SILENT_AFTER_S = 1.0


def running_store() -> StateStore:
    """Every service alive, each having published twice; the vehicle clock at 10 s."""
    store = StateStore(list(TOPICS), rate_window_s=5.0)
    for service, topics in TOPICS.items():
        store.set_alive(service, True)
        for wall_s, sent_s in ((100.0, 9.9), (100.1, 10.0)):
            message = ego_pb2.EgoState(speed_mps=12.0)
            message.header.sent_time_s = sent_s
            store.record(service, topics[0], message, sent_s, wall_s)
    store.note_clock(10.0)
    return store


def report(store: StateStore, wall_s: float = 100.2):
    return health_report(store.snapshot(wall_s), "ego", TOPICS, REQUIRED, SILENT_AFTER_S)


def test_the_vehicle_is_ok_when_every_required_service_is_alive_and_publishing():
    health = report(running_store())
    assert health.status is HealthStatus.OK
    assert all(s.status is ServiceStatus.RUNNING for s in health.services.values())


def test_a_required_service_without_liveliness_degrades_the_vehicle():
    store = running_store()
    store.set_alive("scene", False)
    health = report(store)
    assert health.services["scene"].status is ServiceStatus.DOWN
    assert health.status is HealthStatus.DEGRADED


def test_the_vehicle_is_down_when_no_required_service_is_alive():
    store = running_store()
    for service in TOPICS:
        store.set_alive(service, False)
    assert report(store).status is HealthStatus.DOWN


def test_an_optional_service_that_is_down_leaves_the_vehicle_ok():
    store = running_store()
    store.set_alive("scene", False)
    health = health_report(store.snapshot(100.2), "ego", TOPICS, ["sim", "geolocation"], SILENT_AFTER_S)
    assert health.status is HealthStatus.OK
    assert not health.services["scene"].required


def test_ages_are_measured_on_the_vehicle_clock_not_the_wall_clock():
    store = running_store()
    store.note_clock(10.4)
    health = report(store, wall_s=5000.0)  # wall time far later: the age must not care
    assert abs(health.services["geolocation"].last_message_age_s - 0.4) < 1e-9


def test_a_live_service_whose_last_message_is_too_old_is_silent():
    store = running_store()
    store.note_clock(10.0 + SILENT_AFTER_S + 0.5)
    health = report(store)
    assert health.services["scene"].status is ServiceStatus.SILENT
    assert health.status is HealthStatus.DEGRADED


def test_a_live_service_that_has_never_published_is_silent_with_no_age():
    store = StateStore(["scene"], rate_window_s=5.0)
    store.set_alive("scene", True)
    store.note_clock(3.0)
    health = health_report(store.snapshot(1.0), "ego", {"scene": ["scene"]}, ["scene"], SILENT_AFTER_S)
    assert health.services["scene"].status is ServiceStatus.SILENT
    assert health.services["scene"].last_message_age_s is None


def test_a_message_stamped_just_after_the_gateway_clock_has_age_zero():
    store = running_store()
    store.note_clock(9.99)
    assert report(store).services["geolocation"].last_message_age_s == 0.0


def test_the_simulator_is_named_as_a_world_participant_and_the_others_as_the_vehicle_s():
    health = report(running_store())
    assert health.services["sim"].participant == "world/sim"
    assert health.services["scene"].participant == "ego/scene"
    assert health.services["scene"].topics == ["scene"]


def test_the_state_carries_each_message_as_proto_json_with_proto_field_names():
    store = StateStore(["geolocation", "scene"], rate_window_s=5.0)
    ego = ego_pb2.EgoState(speed_mps=14.5, mode=ego_pb2.LOCALISATION_MODE_GNSS_PRECISE)
    ego.header.sent_time_s = 4.0
    store.record("geolocation", "ego/state", ego, 4.0, wall_s=1.0)
    scene = scene_pb2.Scene(has_forward_mio=True, forward_mio_id=7)
    store.record("scene", "scene", scene, 3.9, wall_s=1.0)
    store.note_clock(4.1)
    state = state_report(store.snapshot(1.0), "ego")
    assert state.ego_state.type_name == "coopdrive.v1.EgoState"
    assert state.ego_state.message["speed_mps"] == 14.5
    assert state.ego_state.message["mode"] == "LOCALISATION_MODE_GNSS_PRECISE"
    assert abs(state.ego_state.age_s - 0.1) < 1e-9
    assert state.scene.message["forward_mio_id"] == 7
    assert state.scene.message["has_mio"] is False  # defaults are spelled out, not omitted
    assert state.planner_state is None


def test_health_shows_the_bus_mode_it_is_given():
    store = StateStore(["scene"], rate_window_s=5.0)
    health = health_report(store.snapshot(1.0), "ego", {"scene": ["scene"]}, ["scene"], SILENT_AFTER_S,
                           bus_mode="plain-loopback")
    assert health.bus_mode == "plain-loopback"
