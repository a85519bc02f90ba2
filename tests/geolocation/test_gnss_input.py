"""Where geolocation's GNSS comes from: its port (a device or pyserial URL, reopened when it drops), published on
gnss/nmea as it arrives; under replay the recorded gnss/nmea instead of the port; a port that cannot be opened
is one line."""

import logging
import socket
import subprocess
import sys
import threading
import time

import pytest
from pydantic import ValidationError

from coopdrive.runtime.clock import WallClock
from coopdrive.runtime.testing import MemoryContext
from coopdrive.services.geolocation.gnss_serial import GnssPortError, GnssSerial
from coopdrive.gnss.nmea_decoder import with_checksum
from coopdrive.services.geolocation.service import GeolocationConfig, GeolocationService, GnssInput, gnss_sources
from coopdrive.services.sim.gnss_pty import GnssPty
from tests.geolocation.nmea_replay import nmea_chunks, replay_chunks

GGA = "GPGGA,1015{:02d}.00,5128.2900,N,00536.0600,E,4,14,0.7,20.5,M,47.0,M,,"
RMC = "GPRMC,1015{:02d}.00,A,5128.2900,N,00536.0600,E,0.02,,200818,,,R"
WAIT_S = 5.0


def epoch(second: int) -> bytes:
    return b"".join((with_checksum(body.format(second)) + "\r\n").encode() for body in (RMC, GGA))


def live_context() -> MemoryContext:
    """A live service's context: wall clock, call_soon at once, hardware opened."""
    return MemoryContext(log=logging.getLogger("test.geolocation"), clock=WallClock(), opens_hardware=True)


def wait_for(condition, timeout_s: float = WAIT_S) -> bool:
    deadline = time.monotonic() + timeout_s
    while time.monotonic() < deadline:
        if condition():
            return True
        time.sleep(0.02)
    return False


def test_the_input_follows_the_config_and_under_replay_the_recorded_chunks_stand_in_for_the_port():
    with_port = GeolocationConfig(gnss_port="/dev/ttyACM0")
    assert gnss_sources(with_port, opens_hardware=True) == {GnssInput.PORT}
    assert gnss_sources(with_port, opens_hardware=False) == {GnssInput.NMEA_TOPIC}
    assert gnss_sources(GeolocationConfig(), True) == {GnssInput.NMEA_TOPIC, GnssInput.FIX_TOPIC}
    assert gnss_sources(GeolocationConfig(gnss_input="fix_topic"), False) == {GnssInput.FIX_TOPIC}
    with pytest.raises(ValidationError, match="gnss_port"):
        GeolocationConfig(gnss_input="port")


def test_replaying_a_service_configured_with_a_port_decodes_gnss_nmea_without_opening_the_port():
    config = GeolocationConfig(gnss_port="/dev/no-such-receiver", gnss_open_timeout_s=0.01, output_rate_hz=10.0)
    chunks = nmea_chunks(epoch(0) + epoch(1), start_s=100.0, period_s=0.5)
    replay = replay_chunks(chunks, config)
    assert [fix.header.sample_time_s for fix in replay.fixes] == [100.0, 101.0]  # each epoch's first chunk
    assert replay.service.serial is None
    assert replay.states[-1].mode != 4  # not LOST


def test_a_live_port_s_bytes_go_on_gnss_nmea_stamped_on_arrival_and_are_decoded(tmp_path):
    ctx = live_context()
    with GnssPty(tmp_path / "gnss0") as pty:
        service = GeolocationService(GeolocationConfig(gnss_port=str(tmp_path / "gnss0")), ctx)
        service.start()
        try:
            before_s = time.time()
            data = epoch(0) + epoch(1) + epoch(2)
            pty.write(data)
            assert wait_for(lambda: sum(len(c.data) for c in ctx.messages("gnss/nmea")) == len(data))
        finally:
            service.stop()
    chunks = ctx.messages("gnss/nmea")
    assert b"".join(chunk.data for chunk in chunks) == data
    assert all(chunk.port == str(tmp_path / "gnss0") for chunk in chunks)
    assert all(before_s <= chunk.header.sample_time_s <= time.time() for chunk in chunks)
    assert len(ctx.messages("ego/gnss")) >= 2


def test_a_pty_that_closes_is_said_to_have_dropped_and_is_reopened_when_it_comes_back(tmp_path, caplog):
    received = bytearray()
    with GnssPty(tmp_path / "gnss0") as first:
        port = GnssSerial(str(tmp_path / "gnss0"), open_timeout_s=1.0, reopen_interval_s=0.1)
        port.start_thread(received.extend)
        first.write(epoch(0))
        assert wait_for(lambda: len(received) == len(epoch(0)))
    try:
        with caplog.at_level(logging.WARNING):
            assert wait_for(lambda: port.counters["gnss_port_drops"] == 1)
            with GnssPty(tmp_path / "gnss0") as second:
                assert wait_for(lambda: port.counters["gnss_port_reopens"] == 1)
                second.write(epoch(1))
                assert wait_for(lambda: len(received) == len(epoch(0) + epoch(1)))
        assert port._thread.is_alive()
    finally:
        port.close()
    assert bytes(received) == epoch(0) + epoch(1)
    assert any("dropped" in r.getMessage() and str(tmp_path / "gnss0") in r.getMessage() for r in caplog.records)


def test_a_receiver_streaming_over_tcp_is_read_through_a_socket_url_and_reconnected(tmp_path):
    server = socket.create_server(("127.0.0.1", 0))
    host, port_number = server.getsockname()

    def serve() -> None:
        for second in (0, 1):  # two connections: the receiver restarts its stream in between
            connection, _ = server.accept()
            time.sleep(0.3)  # pyserial discards what arrives while it opens (as any late joiner of a stream)
            connection.sendall(epoch(second))
            time.sleep(0.2)
            connection.close()

    thread = threading.Thread(target=serve, daemon=True)
    thread.start()
    received = bytearray()
    port = GnssSerial(f"socket://{host}:{port_number}", reopen_interval_s=0.1)
    port.start_thread(received.extend)
    try:
        assert wait_for(lambda: bytes(received) == epoch(0) + epoch(1))
        assert port.counters["gnss_port_reopens"] >= 1
    finally:
        port.close()
        server.close()


def test_a_port_that_cannot_be_opened_is_one_line_and_stop_after_the_failed_start_is_safe():
    service = GeolocationService(GeolocationConfig(gnss_port="socket://127.0.0.1:1"), live_context())
    with pytest.raises(GnssPortError) as error:
        service.start()
    assert "socket://127.0.0.1:1" in str(error.value) and "\n" not in str(error.value)
    service.stop()


def test_coopdrive_service_with_a_missing_port_or_can_interface_ends_with_one_line_naming_it():
    cases = {"/nonexistent": ["gnss_port=/nonexistent", "gnss_open_timeout_s=0.2"],
             "nocan0": ["can_port.interface=socketcan", "can_port.channel=nocan0"]}
    processes = {}
    for device, settings in cases.items():  # both at once: each start-up costs seconds
        command = [sys.executable, "-m", "coopdrive.cli", "service", "geolocation"]
        for setting in settings:
            command += ["--set", setting]
        processes[device] = subprocess.Popen(command, stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
    for device, process in processes.items():
        _, stderr = process.communicate(timeout=60)
        assert process.returncode == 1
        lines = stderr.strip().splitlines()
        assert len(lines) == 1 and "Traceback" not in stderr
        assert device in lines[0]
