"""A service's certificate receives only the topics its declaration says it reads: a subscriber it declares on any
other topic is refused by the router and gets nothing, while its declared subscriptions on the same session work.

In order on the receiving session: its refused subscriber is declared before an allowed one, so once the allowed one
hears, the router has judged both; the publisher's last put before the check is a refused one the router logs, so
every earlier put of that link has been routed by then.
"""

from coopdrive.bus import Bus, BusConfig, topic_named
from tests.bus.secure_bus import VEHICLE, client_config, message, open_as, wait_for_log, wait_until


def test_a_services_certificate_cannot_subscribe_to_a_topic_it_does_not_declare(credentials, router_log):
    heard: list[tuple[str, str]] = []

    def on_sample(sample) -> None:
        topic = str(sample.key_expr).split("/", 2)[2]
        heard.append((topic, topic_named(topic).message_type.FromString(sample.payload.to_bytes()).header.sender))

    control = open_as(credentials, "control")  # reads ego/state, not v2x/cam (which planner and scene read)
    v2x = open_as(credentials, "v2x")
    geolocation = Bus(BusConfig(zenoh_config_file=client_config(credentials, "geolocation")))
    try:
        control.declare_subscriber(f"coopdrive/{VEHICLE}/v2x/cam", on_sample)
        control.declare_subscriber(f"coopdrive/{VEHICLE}/ego/state", on_sample)
        wait_until(lambda: publish_and_check(geolocation, "before", heard), "control heard geolocation's ego/state")
        for _ in range(5):
            v2x.put(f"coopdrive/{VEHICLE}/v2x/cam", message("v2x/cam", "v2x").SerializeToString())
        done = f"coopdrive/{VEHICLE}/v2x-has-put/v2x/cam"
        v2x.put(done, b"")
        wait_for_log(router_log, f"unauthorized to Put (ingress) on {done}")
        wait_until(lambda: publish_and_check(geolocation, "after", heard), "control heard ego/state after v2x/cam")
        assert [topic for topic, _ in heard if topic != "ego/state"] == []
        assert ("ego/state", "after") in heard
    finally:
        geolocation.close()
        v2x.close()
        control.close()


def publish_and_check(publisher: Bus, sender: str, heard: list[tuple[str, str]]) -> bool:
    """Puts ego/state as `sender` unless it was heard already; whether it has been."""
    if ("ego/state", sender) in heard:
        return True
    publisher.publish(VEHICLE, "ego/state", message("ego/state", sender))
    return False
