import datetime as dt
import threading

import pymap3d
import pytest

from coopdrive.runtime.testing import MemoryContext
from coopdrive.services.geolocation.gnss_serial import GnssPortError, GnssSerial
from coopdrive.gnss.nmea_decoder import BadSentence, NmeaDecoder
from coopdrive.services.sim.gnss_pty import GnssPty
from coopdrive.services.sim.gnss_sensor import GnssSensor
from coopdrive.services.sim.sensor_config import FixModeName, GnssConfig, SensorTimingConfig
from coopdrive.services.sim.sensor_timing import sensor_rng
from coopdrive.v1 import gnss_pb2, sim_pb2

ORIGIN = (51.4504, 5.6260, 20.0)
EPOCH = dt.datetime(2016, 5, 28, 10, 0, 0, tzinfo=dt.timezone.utc)
MARK_TIMEOUT_S = 2.0


def _outputs(count: int) -> list:
    sensor = GnssSensor(GnssConfig(fix_mode=FixModeName.RTK_FIXED, timing=SensorTimingConfig(rate_hz=10.0)),
                        sensor_rng(7, "ego", "gnss"), lambda x, y, z: pymap3d.enu2geodetic(x, y, z, *ORIGIN), EPOCH)
    ego = sim_pb2.VehicleTruth(vehicle_id="ego", x_m=120.0, y_m=-35.0, heading_rad=0.3, speed_mps=11.0)
    return [output for k in range(count) for output in sensor.poll(k * 0.1, ego)]


def test_read_until_stops_exactly_at_the_mark_and_the_decoder_gets_each_epoch(tmp_path):
    fixes: list[gnss_pb2.GnssFix] = []
    decoder = NmeaDecoder(fixes.append)
    outputs = _outputs(3)
    with GnssPty(tmp_path / "gnss0") as pty:
        port = GnssSerial(str(tmp_path / "gnss0"), open_timeout_s=1.0)
        try:
            marks = [pty.write(output.data) for output in outputs]  # all written before any read
            for k, mark in enumerate(marks):
                assert port.read_until(mark, MARK_TIMEOUT_S, lambda chunk: decoder.feed(chunk, k * 0.1))
                assert port.read_total == mark
                assert len(fixes) == k + 1  # the next epoch's bytes stay in the port until its mark
        finally:
            port.close()
    for fix, output in zip(fixes, outputs):
        assert fix.latitude_deg == pytest.approx(output.message.latitude_deg, abs=1e-6)
        assert fix.longitude_deg == pytest.approx(output.message.longitude_deg, abs=1e-6)
        assert fix.fix_mode == gnss_pb2.FIX_MODE_RTK_FIXED


def test_a_garbled_sentence_is_counted_and_skipped(tmp_path):
    fixes: list[gnss_pb2.GnssFix] = []
    decoder = NmeaDecoder(fixes.append)
    first, second = _outputs(2)
    garbled = first.sentences[0].replace(b",", b";", 1)  # checksum no longer matches
    with GnssPty(tmp_path / "gnss0") as pty:
        port = GnssSerial(str(tmp_path / "gnss0"), open_timeout_s=1.0)
        try:
            mark = pty.write(garbled + b"".join(first.sentences[1:]) + second.data)
            assert port.read_until(mark, MARK_TIMEOUT_S, lambda chunk: decoder.feed(chunk, 0.2))
        finally:
            port.close()
    assert decoder.bad[BadSentence.BAD_CHECKSUM] == 1
    assert [fix.latitude_deg for fix in fixes][-1] == pytest.approx(second.message.latitude_deg, abs=1e-6)


def test_read_until_returns_false_when_the_mark_is_never_reached(tmp_path):
    with GnssPty(tmp_path / "gnss0") as pty:
        port = GnssSerial(str(tmp_path / "gnss0"), open_timeout_s=1.0)
        try:
            pty.write(b"$short\r\n")
            assert not port.read_until(100, 0.3, lambda chunk: None)
            assert port.read_total == 8
        finally:
            port.close()


def test_the_reader_thread_hands_on_every_byte(tmp_path):
    received = bytearray()
    done = threading.Event()
    data = b"".join(output.data for output in _outputs(3))

    def on_chunk(chunk: bytes) -> None:
        received.extend(chunk)
        if len(received) >= len(data):
            done.set()

    with GnssPty(tmp_path / "gnss0") as pty:
        port = GnssSerial(str(tmp_path / "gnss0"), open_timeout_s=1.0)
        try:
            port.start_thread(on_chunk)
            pty.write(data)
            assert done.wait(5.0)
        finally:
            port.close()
    assert bytes(received) == data


def test_opening_waits_for_a_port_created_later(tmp_path):
    link = tmp_path / "gnss0"
    ptys: list[GnssPty] = []
    timer = threading.Timer(0.2, lambda: ptys.append(GnssPty(link)))
    timer.start()
    try:
        port = GnssSerial(str(link), open_timeout_s=5.0)
        port.close()
    finally:
        timer.join()
        for pty in ptys:
            pty.close()


def test_opening_a_port_that_never_appears_fails_with_one_line_naming_it(tmp_path):
    with pytest.raises(GnssPortError) as error:
        GnssSerial(str(tmp_path / "missing"), open_timeout_s=0.2)
    message = str(error.value)
    assert str(tmp_path / "missing") in message and "\n" not in message


def test_the_service_in_marks_mode_reads_to_each_mark_and_publishes_the_receivers_fixes(tmp_path):
    from coopdrive.services.geolocation.service import GeolocationConfig, GeolocationService

    outputs = _outputs(2)
    with GnssPty(tmp_path / "gnss0") as pty:
        ctx = MemoryContext(opens_hardware=True)
        config = GeolocationConfig(gnss_port=str(tmp_path / "gnss0"), serial_sync="marks",
                                   origin={"lat_deg": ORIGIN[0], "lon_deg": ORIGIN[1], "alt_m": ORIGIN[2]})
        service = GeolocationService(config, ctx)
        service.start()
        try:
            assert "gnss/fix" not in ctx.handlers
            for output in outputs:
                mark = sim_pb2.WireMark(written=pty.write(output.data))
                ctx.deliver("gnss/serial_mark", mark)
            mark = sim_pb2.WireMark(written=pty.written + 10)  # never written: times out, counted
            service.config = config.model_copy(update={"serial_mark_timeout_s": 0.2})
            ctx.deliver("gnss/serial_mark", mark)
        finally:
            service.stop()
    fixes = ctx.messages("ego/gnss")
    assert [fix.latitude_deg for fix in fixes] == pytest.approx([o.message.latitude_deg for o in outputs], abs=1e-6)
    assert service.counters["serial_mark_timeouts"] == 1
    assert service.counters["serial_lost_bytes"] == 10


def test_after_bytes_lost_before_the_open_a_timed_out_mark_realigns_the_next_ones(tmp_path):
    fixes: list[gnss_pb2.GnssFix] = []
    decoder = NmeaDecoder(fixes.append)
    first, second = _outputs(2)
    with GnssPty(tmp_path / "gnss0") as pty:
        lost_mark = pty.write(first.data)  # before the reader opens: flushed by pyserial's open
        port = GnssSerial(str(tmp_path / "gnss0"), open_timeout_s=1.0)
        try:
            assert not port.read_until(lost_mark, 0.2, lambda chunk: decoder.feed(chunk, 0.0))
            assert port.skip_to(lost_mark) == len(first.data)
            assert port.read_until(pty.write(second.data), MARK_TIMEOUT_S, lambda chunk: decoder.feed(chunk, 0.1))
        finally:
            port.close()
    assert [fix.latitude_deg for fix in fixes] == pytest.approx([second.message.latitude_deg], abs=1e-6)


def test_a_port_whose_writer_has_gone_ends_the_read_with_one_line_and_a_count(tmp_path, caplog):
    pty = GnssPty(tmp_path / "gnss0")
    port = GnssSerial(str(tmp_path / "gnss0"), open_timeout_s=1.0)
    try:
        mark = pty.write(_outputs(1)[0].data)
        pty.close()  # the simulator ended before the stack read its last mark
        assert port.read_until(mark + 100, MARK_TIMEOUT_S, lambda chunk: None) is False
    finally:
        port.close()
    assert port.counters["gnss_port_drops"] == 1
    failures = [r.getMessage() for r in caplog.records if "failed while reading" in r.getMessage()]
    assert len(failures) == 1 and "\n" not in failures[0]
