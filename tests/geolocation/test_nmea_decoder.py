import pytest

from coopdrive.gnss.nmea_decoder import BadSentence, NmeaDecoder, SentenceType, with_checksum
from coopdrive.v1 import gnss_pb2

# 51 deg 28.2900' N = 51.4715, 5 deg 36.0600' E = 5.601
GGA = "GPGGA,101530.00,5128.2900,N,00536.0600,E,{quality},14,0.7,20.5,M,47.0,M,1.0,0001"
GST = "GPGST,101530.00,0.02,0.015,0.012,30.0,0.012,0.014,0.030"
RMC = "GPRMC,101530.00,A,5128.2900,N,00536.0600,E,43.2,90.0,231126,,,R"
VTG = "GPVTG,45.0,T,,M,10.8,N,20.0,K,R"


def line(body: str) -> bytes:
    return (with_checksum(body) + "\r\n").encode()


def epoch(quality: int = 4, utc: str = "101530.00") -> bytes:
    return b"".join(line(body.format(quality=quality).replace("101530.00", utc)) for body in (RMC, GGA, GST))


@pytest.fixture
def decoder_and_fixes():
    fixes = []
    return NmeaDecoder(fixes.append), fixes


def test_an_rtk_epoch_of_rmc_gga_gst_becomes_one_fix(decoder_and_fixes):
    decoder, fixes = decoder_and_fixes
    decoder.feed(epoch(), receive_time_s=12.5)
    assert len(fixes) == 1
    fix = fixes[0]
    assert (fix.latitude_deg, fix.longitude_deg) == pytest.approx((51.4715, 5.601))
    assert fix.altitude_m == pytest.approx(67.5)  # 20.5 m above the geoid + 47.0 m separation
    assert fix.fix_mode == gnss_pb2.FIX_MODE_RTK_FIXED
    assert (fix.std_east_m, fix.std_north_m, fix.std_up_m) == pytest.approx((0.014, 0.012, 0.030))
    assert fix.speed_mps == pytest.approx(43.2 * 1852.0 / 3600.0)
    assert fix.course_deg == pytest.approx(90.0)
    assert (fix.satellites, fix.hdop) == (14, pytest.approx(0.7))
    assert fix.header.sample_time_s == 12.5
    assert fix.header.sequence == 1


def test_the_receiver_latency_is_taken_off_the_sample_time():
    fixes = []
    NmeaDecoder(fixes.append, receiver_latency_s=0.03).feed(epoch(), receive_time_s=1.0)
    assert fixes[0].header.sample_time_s == pytest.approx(0.97)


def test_a_sentence_with_a_bad_checksum_is_counted_and_skipped(decoder_and_fixes):
    decoder, fixes = decoder_and_fixes
    corrupted = line(GGA.format(quality=4)).replace(b"5128.2900", b"5128.2901")
    decoder.feed(line(RMC) + corrupted + line(GST), receive_time_s=1.0)
    decoder.flush()
    assert fixes == []
    assert decoder.bad[BadSentence.BAD_CHECKSUM] == 1
    decoder.feed(epoch(utc="101530.05"), receive_time_s=1.05)
    assert len(fixes) == 1


def test_sentences_without_checksum_or_start_or_that_do_not_parse_are_counted_by_reason(decoder_and_fixes):
    decoder, _ = decoder_and_fixes
    decoder.feed(b"$GPGGA,101530.00,5128.2900,N\r\n" + b"GPGGA,1*00\r\n" + line("GPGGA,xx,yy") + b"\xff\xfe\n", 0.0)
    assert decoder.bad[BadSentence.NO_CHECKSUM] == 1
    assert decoder.bad[BadSentence.NO_START] == 1
    assert decoder.bad[BadSentence.UNPARSABLE] == 1
    assert decoder.bad[BadSentence.NOT_ASCII] == 1


def test_a_sentence_split_across_reads_is_buffered_until_its_end(decoder_and_fixes):
    decoder, fixes = decoder_and_fixes
    data = epoch()
    for start in range(0, len(data), 7):
        decoder.feed(data[start:start + 7], receive_time_s=2.0)
    assert len(fixes) == 1
    assert sum(decoder.bad.values()) == 0


def test_an_endless_line_is_dropped_as_too_long(decoder_and_fixes):
    decoder, _ = decoder_and_fixes
    decoder.feed(b"$" + b"A" * 500, 0.0)
    assert decoder.bad[BadSentence.TOO_LONG] == 1


@pytest.mark.parametrize(("quality", "fix_mode"), [
    (4, gnss_pb2.FIX_MODE_RTK_FIXED),
    (5, gnss_pb2.FIX_MODE_RTK_FLOAT),
    (2, gnss_pb2.FIX_MODE_DGPS),
    (9, gnss_pb2.FIX_MODE_SBAS),
    (1, gnss_pb2.FIX_MODE_SINGLE),
    (0, gnss_pb2.FIX_MODE_NO_FIX),
    (6, gnss_pb2.FIX_MODE_NO_FIX),
])
def test_the_gga_quality_indicator_maps_to_the_fix_mode(quality, fix_mode):
    fixes = []
    NmeaDecoder(fixes.append).feed(epoch(quality=quality), 0.0)
    assert fixes[0].fix_mode == fix_mode


def test_a_receiver_reporting_sbas_as_quality_2_is_decoded_as_sbas():
    fixes = []
    NmeaDecoder(fixes.append, quality2_fix_mode=gnss_pb2.FIX_MODE_SBAS).feed(epoch(quality=2), 0.0)
    assert fixes[0].fix_mode == gnss_pb2.FIX_MODE_SBAS


def test_a_fix_without_position_carries_no_coordinates():
    fixes = []
    NmeaDecoder(fixes.append).feed(epoch(quality=0), 0.0)
    assert (fixes[0].latitude_deg, fixes[0].longitude_deg) == (0.0, 0.0)


def test_an_unknown_quality_indicator_is_counted(decoder_and_fixes):
    decoder, fixes = decoder_and_fixes
    decoder.feed(line(GGA.format(quality=3)), 0.0)
    decoder.flush()
    assert fixes == [] and decoder.bad[BadSentence.UNKNOWN_QUALITY] == 1


def test_an_epoch_missing_an_expected_sentence_is_emitted_when_the_next_epoch_starts(decoder_and_fixes):
    decoder, fixes = decoder_and_fixes
    decoder.feed(line(GGA.format(quality=5)), 1.0)
    assert fixes == []
    decoder.feed(line(RMC.replace("101530.00", "101530.05")), 1.05)
    assert len(fixes) == 1 and fixes[0].std_east_m == 0.0 and fixes[0].header.sample_time_s == 1.0


def test_vtg_gives_speed_and_course_when_only_gga_is_expected():
    fixes = []
    decoder = NmeaDecoder(fixes.append, expected_sentences=frozenset({SentenceType.GGA, SentenceType.VTG}))
    decoder.feed(line(GGA.format(quality=1)) + line(VTG), 0.0)
    assert fixes[0].speed_mps == pytest.approx(20.0 / 3.6)
    assert fixes[0].course_deg == pytest.approx(45.0)


def test_other_sentence_types_are_ignored_not_counted_as_bad(decoder_and_fixes):
    decoder, _ = decoder_and_fixes
    decoder.feed(line("GPGSA,A,3,04,05,,09,12,,,24,,,,,2.5,1.3,2.1"), 0.0)
    assert decoder.ignored == 1 and sum(decoder.bad.values()) == 0


def test_a_sentence_repeated_after_its_epoch_was_emitted_is_counted_late(decoder_and_fixes):
    decoder, fixes = decoder_and_fixes
    decoder.feed(epoch() + line(GST), 0.0)
    assert len(fixes) == 1 and decoder.late == 1
