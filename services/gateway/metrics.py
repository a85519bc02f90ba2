"""GatewayMetrics: the vehicle's state as Prometheus gauges, on a registry of its own.

Gauges are set from a store snapshot when scraped, so they cost nothing between scrapes; the
gateway's own counters (commands, dropped live frames) are counted as they happen.
"""

from __future__ import annotations

from prometheus_client import CollectorRegistry, Counter, Gauge, generate_latest
from prometheus_client.exposition import CONTENT_TYPE_LATEST

from coopdrive.services.gateway.state_store import StoreSnapshot
from coopdrive.services.gateway.view_models import LinkStateName
from coopdrive.services.gateway.views import forward_gap_m, time_gap_s, v2x_view

CONTENT_TYPE = CONTENT_TYPE_LATEST
NAMESPACE = "coopdrive"


class GatewayMetrics:
    def __init__(self, vehicle_id: str):
        self.vehicle_id = vehicle_id
        self.registry = CollectorRegistry(auto_describe=True)
        r, ns = self.registry, NAMESPACE
        self.clock = Gauge("clock_seconds", "Vehicle clock (simulation time in a run).", namespace=ns, registry=r)
        self.speed = Gauge("ego_speed_mps", "Ego speed, m/s.", namespace=ns, registry=r)
        self.accel = Gauge("ego_accel_mps2", "Ego acceleration, m/s^2.", namespace=ns, registry=r)
        self.gap = Gauge("gap_m", "Gap to the forward most-important object, m (NaN without one).",
                         namespace=ns, registry=r)
        self.time_gap = Gauge("time_gap_s", "Gap over ego speed, s (NaN without a gap or standing).",
                              namespace=ns, registry=r)
        self.scene_objects = Gauge("scene_objects", "Objects in the latest scene.", namespace=ns, registry=r)
        self.service_alive = Gauge("service_alive", "1 while the service's liveliness token is present.",
                                   ["service"], namespace=ns, registry=r)
        self.message_rate = Gauge("service_message_rate_hz", "Messages per second from the service, all topics.",
                                  ["service"], namespace=ns, registry=r)
        self.stations = Gauge("v2x_stations", "Remote ITS stations by link state.", ["state"], namespace=ns,
                              registry=r)
        self.v2x_packets_received = Gauge("v2x_packets_received", "Packets received by the v2x service.",
                                          namespace=ns, registry=r)
        self.ws_clients = Gauge("gateway_ws_clients", "WebSocket clients connected to /ws.", namespace=ns,
                                registry=r)
        self.ws_dropped = Counter("gateway_ws_frames_dropped", "Live frames dropped for slow WebSocket clients.",
                                  namespace=ns, registry=r)
        self.commands = Counter("gateway_commands", "Commands received, by command and outcome.",
                                ["command", "outcome"], namespace=ns, registry=r)

    def update(self, snapshot: StoreSnapshot, ws_clients: int) -> None:
        nan = float("nan")
        self.clock.set(snapshot.clock_s if snapshot.clock_s is not None else nan)
        ego = snapshot.latest.get("ego/state")
        self.speed.set(ego.message.speed_mps if ego else nan)
        self.accel.set(ego.message.accel_mps2 if ego else nan)
        scene = snapshot.latest.get("scene")
        gap = forward_gap_m(scene.message if scene else None)
        self.gap.set(nan if gap is None else gap)
        time_gap = time_gap_s(gap, ego.message.speed_mps if ego else None)
        self.time_gap.set(nan if time_gap is None else time_gap)
        self.scene_objects.set(len(scene.message.objects) if scene else 0)
        for service, activity in snapshot.services.items():
            self.service_alive.labels(service).set(1 if activity.alive else 0)
            self.message_rate.labels(service).set(activity.message_rate_hz)
        v2x = v2x_view(snapshot, self.vehicle_id)
        for state in LinkStateName:
            self.stations.labels(state.value).set(sum(s.state is state for s in v2x.stations))
        self.v2x_packets_received.set(v2x.packets_received)
        self.ws_clients.set(ws_clients)

    def render(self) -> bytes:
        return generate_latest(self.registry)
