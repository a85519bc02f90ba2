"""The vehicle's bus as `coopdrive pki bus` makes it, with a real `coopdrive router` process: who may connect, and
which puts reach whom.

Each client is a session of its own over TLS to the router (a transport the router judges apart from the others).
A forged put "never arrives" is checked on the receiving side, in order: the router's log says it judged the
forger's last put (every earlier put of that link was routed or dropped before it), and then the topic's owner
puts once more; that put reaches the reader, so a forged one the router had let through would have reached it first.
"""

import datetime
import queue
import time
from pathlib import Path

import pytest
import zenoh

from coopdrive.bus import Bus, BusConfig
from coopdrive.bus.bus_authority import BusAuthority, write_pair
from coopdrive.bus.bus_credentials import CERTIFICATE, KEY
from tests.bus.secure_bus import (DEADLINE_S, OBSERVER, VEHICLE, client_config, coopdrive, message, open_as,
                                  wait_for_log, wait_until)

# A certificate valid this long from its issue: long enough to connect on a loaded machine, short enough to wait for.
CONNECTED_VALIDITY_S = 8.0
SECONDS_PER_DAY = 86400.0


def publish_until_heard(owner: Bus, topic: str, sender: str, heard: queue.Queue) -> None:
    """Puts until the reader has one (the owner's Bus puts only once the router has told it someone listens)."""
    end = time.monotonic() + DEADLINE_S
    while time.monotonic() < end:
        owner.publish(VEHICLE, topic, message(topic, sender))
        try:
            wait_for_sender(heard, sender, timeout_s=0.2)
            return
        except queue.Empty:
            continue
    raise AssertionError(f"{topic} from {sender} never reached its reader")


def wait_for_sender(heard: queue.Queue, sender: str, timeout_s: float):
    end = time.monotonic() + timeout_s
    while True:
        item = heard.get(timeout=max(0.0, end - time.monotonic()))
        if item.message.header.sender == sender:
            return item


def forged_puts_reach_nobody(credentials: Path, router_log: Path, forger: str, topic: str, owner: str,
                             reader: str) -> list[str]:
    """`forger` puts `topic` (which `owner` publishes and `reader` reads) on the vehicle; returns the senders of
    what the reader received, in order without repeats, from the owner's first put to its put after the router
    judged the forger's last."""
    heard: queue.Queue = queue.Queue()
    senders: list[str] = []

    def on_message(envelope) -> None:
        senders.append(envelope.message.header.sender)
        heard.put(envelope)

    reading = Bus(BusConfig(zenoh_config_file=client_config(credentials, reader)))
    owning = Bus(BusConfig(zenoh_config_file=client_config(credentials, owner)))
    forging = open_as(credentials, forger)
    try:
        reading.subscribe(VEHICLE, topic, on_message)
        publish_until_heard(owning, topic, "owner before", heard)
        forged = message(topic, forger).SerializeToString()
        for _ in range(5):
            forging.put(f"coopdrive/{VEHICLE}/{topic}", forged)
        done = f"coopdrive/{VEHICLE}/{forger}-has-forged/{topic}"
        forging.put(done, b"")
        wait_for_log(router_log, f"unauthorized to Put (ingress) on {done}")
        owning.publish(VEHICLE, topic, message(topic, "owner after"))
        wait_for_sender(heard, "owner after", DEADLINE_S)
        return list(dict.fromkeys(senders))
    finally:
        forging.close()
        owning.close()
        reading.close()


def test_a_client_without_a_certificate_cannot_connect(credentials, router_log):
    config = zenoh.Config.from_file(client_config(credentials, "control"))
    config.insert_json5("transport/link/tls/connect_certificate", "null")
    config.insert_json5("transport/link/tls/connect_private_key", "null")
    with pytest.raises(zenoh.ZError, match="Unable to connect"):
        zenoh.open(config)
    with open_as(credentials, "control") as admitted:
        assert list(admitted.info.routers_zid())


def test_a_client_with_a_certificate_from_another_ca_cannot_connect(credentials, router_log, tmp_path):
    other = BusAuthority.create("another vehicle's CA", days=1)
    certificate, key = other.issue("control", days=1)
    write_pair(certificate, key, tmp_path / "rogue.pem", tmp_path / "rogue-key.pem")
    config = zenoh.Config.from_file(client_config(credentials, "control"))
    config.insert_json5("transport/link/tls/connect_certificate", f'"{tmp_path / "rogue.pem"}"')
    config.insert_json5("transport/link/tls/connect_private_key", f'"{tmp_path / "rogue-key.pem"}"')
    with pytest.raises(zenoh.ZError, match="Unable to connect"):
        zenoh.open(config)
    wait_for_log(router_log, "invalid peer certificate: UnknownIssuer")


def test_an_observer_subscribes_but_its_commands_and_behaviours_reach_neither_actuation_nor_control(
        credentials, router_log):
    seen: set[str] = set()
    with open_as(credentials, OBSERVER) as observer:
        observer.declare_subscriber(f"coopdrive/{VEHICLE}/**", lambda sample: seen.add(str(sample.key_expr)))
        assert forged_puts_reach_nobody(credentials, router_log, OBSERVER, "control/command", "control",
                                        "actuation") == ["owner before", "owner after"]
        assert forged_puts_reach_nobody(credentials, router_log, OBSERVER, "planner/behaviour", "planner",
                                        "control") == ["owner before", "owner after"]
        owners = {f"coopdrive/{VEHICLE}/control/command", f"coopdrive/{VEHICLE}/planner/behaviour"}
        wait_until(lambda: owners <= seen, "the observer received control's and planner's puts")


def test_the_gateways_certificate_cannot_publish_the_cars_can_frames(credentials, router_log):
    assert forged_puts_reach_nobody(credentials, router_log, "gateway", "can/vehicle", "actuation",
                                    "geolocation") == ["owner before", "owner after"]


def test_a_services_certificate_cannot_publish_another_services_topic(credentials, router_log):
    assert forged_puts_reach_nobody(credentials, router_log, "planner", "control/command", "control",
                                    "actuation") == ["owner before", "owner after"]


def test_a_service_with_an_expired_certificate_is_refused_and_says_so_in_one_line(credentials, router_log):
    authority = BusAuthority.load(credentials / "ca" / "ca.pem", credentials / "ca" / "ca-key.pem")
    three_days_ago = datetime.datetime.now(datetime.timezone.utc) - datetime.timedelta(days=3)
    expired = authority.issue("control", days=1, now=three_days_ago)
    write_pair(*expired, credentials / "control" / CERTIFICATE, credentials / "control" / KEY)
    with pytest.raises(zenoh.ZError, match="Unable to connect"):
        open_as(credentials, "control")
    wait_for_log(router_log, "invalid peer certificate: certificate expired")
    result = coopdrive("service", "control", "--vehicle", VEHICLE, "--zenoh-config",
                       client_config(credentials, "control"))
    assert result.returncode == 2
    assert result.stderr.count("\n") == 1, result.stderr
    assert f"certificate {credentials / 'control' / CERTIFICATE} expired on" in result.stderr
    assert "coopdrive pki bus DIR --vehicle ID" in result.stderr


def test_a_session_whose_certificate_expires_while_connected_is_cut_off_by_the_router(credentials, router_log):
    authority = BusAuthority.load(credentials / "ca" / "ca.pem", credentials / "ca" / "ca-key.pem")
    write_pair(*authority.issue("control", days=CONNECTED_VALIDITY_S / SECONDS_PER_DAY),
               credentials / "control" / CERTIFICATE, credentials / "control" / KEY)
    with open_as(credentials, "control") as session:
        assert list(session.info.routers_zid())
        wait_until(lambda: not list(session.info.routers_zid()), "the router closed the expired certificate's link")
    wait_for_log(router_log, "remote certificate chain expired")
