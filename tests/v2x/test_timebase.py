from datetime import datetime, timezone

from hypothesis import given
from hypothesis import strategies as st

from coopdrive.v2x import timebase


def test_the_its_epoch_is_tai_zero():
    assert timebase.tai_ms_from_utc(datetime(2004, 1, 1, tzinfo=timezone.utc)) == 0


def test_five_leap_seconds_were_added_between_2004_and_2017():
    utc = datetime(2017, 1, 1, tzinfo=timezone.utc)
    without_leaps_ms = round((utc - datetime(2004, 1, 1, tzinfo=timezone.utc)).total_seconds() * 1000)
    assert timebase.tai_ms_from_utc(utc) - without_leaps_ms == 5000


def test_a_gcdc_2016_timestamp_has_four_leap_seconds():
    utc = datetime(2016, 5, 28, 12, 0, tzinfo=timezone.utc)
    without_leaps_ms = round((utc - datetime(2004, 1, 1, tzinfo=timezone.utc)).total_seconds() * 1000)
    assert timebase.tai_ms_from_utc(utc) == without_leaps_ms + 4000


def test_generation_delta_time_is_tai_milliseconds_modulo_65536():
    assert timebase.generation_delta_time_ms(65_536 * 7 + 1234) == 1234


def test_the_full_time_is_recovered_across_a_wrap_of_the_delta():
    sent_tai_ms = 65_536 * 1000 - 20  # delta 65516, just before the wrap
    received_tai_ms = sent_tai_ms + 50  # delta of the receive time has wrapped to 30
    assert timebase.tai_ms_from_delta(timebase.generation_delta_time_ms(sent_tai_ms), received_tai_ms) == sent_tai_ms


@given(st.integers(min_value=40_000, max_value=2**42), st.integers(min_value=-32_767, max_value=32_767))
def test_any_time_within_32_seconds_of_the_reference_is_recovered(reference_tai_ms, age_ms):
    sent = reference_tai_ms - age_ms
    assert timebase.tai_ms_from_delta(timebase.generation_delta_time_ms(sent), reference_tai_ms) == sent


@given(st.floats(min_value=1.1e9, max_value=2.5e9))
def test_unix_time_survives_the_round_trip_through_tai(unix_s):
    assert abs(timebase.unix_s_from_tai_ms(timebase.tai_ms_from_unix_s(unix_s)) - unix_s) < 1e-3
