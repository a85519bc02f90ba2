import datetime as dt
import os

import pymap3d
import pynmea2
import pytest
import serial

from coopdrive.services.sim.gnss_pty import GnssPty
from coopdrive.services.sim.gnss_sensor import GnssSensor
from coopdrive.services.sim.sensor_config import FixModeName, GnssConfig, SensorTimingConfig
from coopdrive.services.sim.sensor_timing import sensor_rng
from coopdrive.v1 import sim_pb2

ORIGIN = (51.4504, 5.6260, 20.0)
EPOCH = dt.datetime(2016, 5, 28, 10, 0, 0, tzinfo=dt.timezone.utc)
# Heudiasyc Table 1: GGA quality per fix mode (SBAS as the configured sbas_gga_quality, 9 by default).
GGA_QUALITY = {FixModeName.SINGLE: 1, FixModeName.DGPS: 2, FixModeName.SBAS: 9, FixModeName.RTK_FLOAT: 5,
               FixModeName.RTK_FIXED: 4}


def _sensor(fix_mode: FixModeName) -> GnssSensor:
    config = GnssConfig(fix_mode=fix_mode, timing=SensorTimingConfig(rate_hz=10.0))
    return GnssSensor(config, sensor_rng(7, "ego", "gnss"),
                      lambda x, y, z: pymap3d.enu2geodetic(x, y, z, *ORIGIN), EPOCH)


def _epochs(sensor: GnssSensor, count: int) -> list:
    ego = sim_pb2.VehicleTruth(vehicle_id="ego", x_m=120.0, y_m=-35.0, heading_rad=0.3, speed_mps=11.0)
    return [output for k in range(count) for output in sensor.poll(k * 0.1, ego)]


def _read_exactly(port: serial.Serial, count: int) -> bytes:
    data = b""
    for _ in range(100):
        data += port.read(count - len(data))
        if len(data) == count:
            break
    return data


@pytest.mark.parametrize("mode", list(GGA_QUALITY))
def test_every_sentence_written_to_the_pty_parses_with_pynmea2_and_matches_the_fix(tmp_path, mode):
    with GnssPty(tmp_path / "gnss0") as pty:
        port = serial.Serial(str(tmp_path / "gnss0"), 115200, timeout=0.5)
        try:
            for output in _epochs(_sensor(mode), 3):
                written_before = pty.written
                assert pty.write(output.data) == written_before + len(output.data)
                lines = _read_exactly(port, len(output.data)).decode("ascii").splitlines()
                parsed = {type(s).__name__: s for s in map(pynmea2.parse, lines)}
                assert set(parsed) == {"GGA", "RMC", "GST", "VTG"}
                assert parsed["GGA"].latitude == pytest.approx(output.message.latitude_deg, abs=1e-6)
                assert parsed["GGA"].longitude == pytest.approx(output.message.longitude_deg, abs=1e-6)
                assert parsed["RMC"].latitude == pytest.approx(output.message.latitude_deg, abs=1e-6)
                assert parsed["RMC"].longitude == pytest.approx(output.message.longitude_deg, abs=1e-6)
                assert parsed["GGA"].gps_qual == GGA_QUALITY[mode]
        finally:
            port.close()


def test_the_pty_passes_bytes_unchanged_in_raw_mode(tmp_path):
    data = b"$GNTXT,01*00\r\n\x03\x11\r\r\n"
    with GnssPty(tmp_path / "gnss0") as pty:
        with serial.Serial(str(tmp_path / "gnss0"), timeout=0.5) as port:
            pty.write(data)
            assert _read_exactly(port, len(data)) == data


def test_writes_before_any_reader_opens_the_port_do_not_fail(tmp_path):
    # pyserial flushes the input on open, so the reader sees only what is written after it opened.
    with GnssPty(tmp_path / "gnss0") as pty:
        assert pty.write(b"$early\r\n") == 8
        with serial.Serial(str(tmp_path / "gnss0"), timeout=0.5) as port:
            assert pty.write(b"$later\r\n") == 16
            assert _read_exactly(port, 8) == b"$later\r\n"


def test_the_link_points_at_the_slave_and_close_removes_it(tmp_path):
    link = tmp_path / "dev" / "gnss0"
    link.parent.mkdir()
    link.symlink_to("/nonexistent")  # stale, from an earlier run
    pty = GnssPty(link)
    assert os.path.realpath(link) == os.path.realpath(pty.device)
    pty.close()
    assert not link.is_symlink()
    pty.close()
