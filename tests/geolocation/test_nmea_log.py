"""An NMEA log file read as the chunks its receiver's port would have delivered, stamped with the receiver's UTC."""

import datetime

from coopdrive.gnss.nmea_decoder import with_checksum
from coopdrive.services.geolocation.nmea_log import read_nmea_log
from tests.shared_data import shared_file


def utc_s(*args) -> float:
    return datetime.datetime(*args, tzinfo=datetime.timezone.utc).timestamp()


def test_every_byte_but_gpsd_s_comment_lines_is_kept_in_order():
    path = shared_file("gnss/gpsd_bundg_zeus_9.log")
    log = read_nmea_log(path)
    kept = b"".join(line for line in path.read_bytes().splitlines(keepends=True) if not line.startswith(b"#"))
    assert b"".join(data for _, data in log.chunks) == kept
    assert log.comment_lines == 10


def test_stamps_are_the_gga_rmc_utc_on_the_rmc_date_and_never_go_back():
    log = read_nmea_log(shared_file("gnss/gpsd_bundg_zeus_9.log"))
    times_s = [time_s for time_s, _ in log.chunks]
    assert log.dated and times_s[0] == utc_s(2018, 8, 20, 9, 47, 36)  # the first GGA, dated by the first RMC
    assert all(later > earlier for earlier, later in zip(times_s, times_s[1:]))
    assert times_s[-1] - times_s[0] < 300.0


def test_lines_before_the_first_time_take_the_first_time_here_from_zda():
    log = read_nmea_log(shared_file("gnss/gpsd_hemi.log"))
    first_s, first_chunk = log.chunks[0]
    assert first_s == utc_s(2018, 9, 7, 19, 39, 13)
    assert first_chunk.startswith(b"$GPHDT,,T*1B")


def test_a_log_crossing_midnight_without_a_new_date_keeps_counting_up(tmp_path):
    gga = "GPGGA,{},5128.2900,N,00536.0600,E,1,14,0.7,20.5,M,47.0,M,,"
    rmc = "GPRMC,235959.00,A,5128.2900,N,00536.0600,E,0.0,,311218,,,A"
    path = tmp_path / "midnight.nmea"
    path.write_text("\n".join(with_checksum(body) for body in (rmc, gga.format("235959.00"), gga.format("000000.00"))))
    times_s = [time_s for time_s, _ in read_nmea_log(path).chunks]
    assert times_s == [utc_s(2018, 12, 31, 23, 59, 59), utc_s(2019, 1, 1, 0, 0, 0)]


def test_a_log_without_any_date_is_timed_on_1970_01_01(tmp_path):
    path = tmp_path / "undated.nmea"
    path.write_text(with_checksum("GPGGA,101530.00,5128.2900,N,00536.0600,E,1,14,0.7,20.5,M,47.0,M,,") + "\n")
    log = read_nmea_log(path)
    assert not log.dated and log.chunks[0][0] == 10 * 3600 + 15 * 60 + 30


def test_at_a_stated_rate_each_gga_starts_the_next_epoch():
    log = read_nmea_log(shared_file("gnss/gpsd_ublox-neo-m9n-nmea.log"), rate_hz=2.0, start_s=100.0)
    times_s = [time_s for time_s, _ in log.chunks]
    assert times_s[0] == 100.0 and times_s[-1] == 100.0 + 60 / 2.0  # 61 GGA, 0.5 s apart
    assert all(b > a for a, b in zip(times_s, times_s[1:]))
