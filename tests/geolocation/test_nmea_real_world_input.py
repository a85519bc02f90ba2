"""NMEA as receivers really send it: dual-antenna headings, GNS, no-fix sentences, dates; and a real log damaged
(truncated lines, bad checksums, binary junk) decodes to the same fixes with every damage counted by reason."""

import random

import pytest

from coopdrive.gnss.nmea_decoder import BadSentence, NmeaDecoder, SentenceType, with_checksum
from coopdrive.services.geolocation.nmea_log import read_nmea_log
from coopdrive.v1 import gnss_pb2
from tests.shared_data import shared_file

GGA = "GPGGA,101530.00,5128.2900,N,00536.0600,E,1,14,0.7,20.5,M,47.0,M,,"


def line(body: str) -> bytes:
    return (with_checksum(body) + "\r\n").encode()


def decode(data: bytes, **options) -> tuple[NmeaDecoder, list[gnss_pb2.GnssFix]]:
    fixes: list[gnss_pb2.GnssFix] = []
    decoder = NmeaDecoder(fixes.append, **options)
    decoder.feed(data, 0.0)
    decoder.flush()
    return decoder, fixes


@pytest.mark.parametrize("talker", ["GP", "GN", "HE"])
def test_a_true_heading_sent_before_its_gga_joins_that_epoch_whatever_the_talker(talker):
    _, fixes = decode(line(f"{talker}HDT,274.07,T") + line(GGA))
    assert fixes[0].heading_valid and fixes[0].heading_deg == pytest.approx(274.07)


def test_ths_gives_the_heading_only_when_its_mode_says_it_was_measured():
    _, fixes = decode(line("GNTHS,77.52,A") + line(GGA) + line("GNTHS,12.0,V") + line(GGA.replace("30.00", "31.00")))
    assert [(f.heading_valid, round(f.heading_deg, 2)) for f in fixes] == [(True, 77.52), (False, 0.0)]


def test_an_empty_hdt_leaves_the_heading_unknown():
    _, fixes = decode(line("GPHDT,,T") + line(GGA))
    assert not fixes[0].heading_valid


def test_gns_gives_the_position_of_a_receiver_without_gga():
    decoder, fixes = decode(line("GNGNS,101530.00,5128.2900,N,00536.0600,E,ADN,12,0.8,20.5,47.0,,,V"))
    assert (fixes[0].latitude_deg, fixes[0].longitude_deg) == pytest.approx((51.4715, 5.601))
    assert fixes[0].fix_mode == gnss_pb2.FIX_MODE_DGPS  # the best of the constellations' letters
    assert decoder.sentences[SentenceType.GNS] == 1


def test_sentences_of_a_receiver_without_a_fix_are_counted_as_no_fix_not_as_bad():
    decoder, fixes = decode(line("GPGGA,,,,,,0,,,,M,,M,,") + line("GPRMC,,V,,,,,,,,,,N") + line("GPVTG,,T,,M,,N,,K,N"))
    assert fixes == [] and decoder.no_fix == 3 and sum(decoder.bad.values()) == 0


def test_a_fix_is_dated_by_zda_or_rmc_and_a_speed_at_a_standstill_is_a_measurement():
    rmc = "GNRMC,101530.00,A,5128.2900,N,00536.0600,E,0.040,,200818,,,D"
    _, fixes = decode(line("GPZDA,101529.00,19,08,2018,00,00") + line(rmc) + line(GGA))
    assert fixes[0].utc_time_s == 1534760130.0  # 2018-08-20 10:15:30 UTC, the RMC's date
    assert fixes[0].velocity_valid and fixes[0].speed_mps == pytest.approx(0.040 * 1852 / 3600)


def test_the_receiver_s_epoch_layout_is_learned_so_later_epochs_are_emitted_as_soon_as_complete():
    fixes: list[gnss_pb2.GnssFix] = []
    decoder = NmeaDecoder(fixes.append)  # expects a GST this receiver never sends
    emitted = []
    for second in range(3):
        epoch = line(GGA.replace("30.00", f"3{second}.00")) + line("GPVTG,45.0,T,,M,10.8,N,20.0,K,A")
        decoder.feed(epoch, float(second))
        emitted.append(len(fixes))
    assert emitted == [0, 2, 3]  # the first when the second began; later ones at once: their layout is known


def damaged(data: bytes, seed: int) -> tuple[bytes, dict[BadSentence, int]]:
    """The log with every 7th line cut short, every 11th with a wrong checksum, binary junk lines between."""
    rng = random.Random(seed)
    out, damage = [], {BadSentence.NO_CHECKSUM: 0, BadSentence.BAD_CHECKSUM: 0, BadSentence.NOT_ASCII: 0}
    for index, raw in enumerate(data.splitlines(keepends=True)):
        if index % 7 == 3 and raw.startswith(b"$GPGSV"):
            out.append(raw[: len(raw) // 2] + b"\r\n")
            damage[BadSentence.NO_CHECKSUM] += 1
        elif index % 11 == 5 and raw.startswith(b"$GPGSV"):
            out.append(raw.replace(b"*", b"0*", 1))
            damage[BadSentence.BAD_CHECKSUM] += 1
        else:
            out.append(raw)
        if index % 13 == 0:
            out.append(bytes([0xB5, 0x62]) + bytes(rng.randrange(128, 256) for _ in range(20)) + b"\n")
            damage[BadSentence.NOT_ASCII] += 1
    return b"".join(out), damage


def test_a_damaged_real_log_decodes_to_the_same_fixes_and_counts_each_damage_by_reason():
    clean = b"".join(data for _, data in read_nmea_log(shared_file("gnss/gpsd_ublox-neo-m9n-nmea.log")).chunks)
    broken, damage = damaged(clean, seed=3)
    clean_decoder, clean_fixes = decode(clean)
    decoder, fixes = decode(broken)
    assert [f.SerializeToString() for f in fixes] == [f.SerializeToString() for f in clean_fixes]
    assert len(fixes) == 61
    assert {reason: decoder.bad[reason] for reason in damage} == damage
    assert sum(decoder.bad.values()) == sum(damage.values()) > 0
    assert sum(clean_decoder.bad.values()) == 0


def test_binary_junk_without_a_line_end_before_a_sentence_loses_only_the_junk():
    junk = bytes(range(128, 256)) * 3
    decoder, fixes = decode(junk + line(GGA))  # junk and sentence on one line
    assert len(fixes) == 1 and decoder.bad[BadSentence.NOT_ASCII] == 1
    fixes.clear()
    decoder.feed(junk, 1.0)  # junk alone overflows the line buffer, then the sentence comes
    decoder.feed(line(GGA.replace("30.00", "31.00")), 1.1)
    decoder.flush()
    assert len(fixes) == 1 and decoder.bad[BadSentence.TOO_LONG] == 1


def test_two_sentences_run_together_by_a_lost_line_end_are_both_read():
    cut = line(GGA)[:30]
    decoder, fixes = decode(cut + line(GGA.replace("30.00", "31.00")))
    assert len(fixes) == 1 and decoder.bad[BadSentence.NO_CHECKSUM] == 1


def test_random_bytes_never_crash_the_decoder():
    rng = random.Random(11)
    decoder, _ = decode(bytes(rng.randrange(256) for _ in range(20000)) + b"$GP*\n$*00\n$,,,*\n")
    assert sum(decoder.bad.values()) > 0
