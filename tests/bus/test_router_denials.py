"""`coopdrive router --count-denials` counts what its access control refused and prints the count on its output;
the access control's other trace lines, which the user did not ask for, stay out of it."""

import subprocess

from tests.bus.secure_bus import OBSERVER, VEHICLE, open_as, wait_for_log


def test_the_router_counts_an_observers_refused_command_and_names_its_key(spawn, credentials, router_endpoint,
                                                                           tmp_path):
    log = tmp_path / "router.log"
    with open(log, "w") as output:
        spawn("router", "--config", str(credentials / "router" / "zenohd.json5"), "--listen", router_endpoint,
              "--count-denials", stdout=output, stderr=subprocess.STDOUT)
    wait_for_log(log, "listening")
    with open_as(credentials, OBSERVER) as observer:
        observer.put(f"coopdrive/{VEHICLE}/control/command", b"forged")
        wait_for_log(log, "access control denials: 1 (last: Put (ingress) on "
                          f"coopdrive/{VEHICLE}/control/command")
    assert "unauthorized" not in log.read_text()
