import datetime as dt
import math

import numpy as np
import pymap3d
import pynmea2
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from coopdrive.services.sim.gnss_sensor import GnssSensor, axis_sigma_m
from coopdrive.services.sim.nmea_writer import NmeaFix, NmeaWriter, checksum
from coopdrive.services.sim.sensor_config import FixModeName, GnssConfig, SensorTimingConfig
from coopdrive.services.sim.sensor_timing import sensor_rng
from coopdrive.v1 import gnss_pb2, sim_pb2
from coopdrive.services.sim.world_profile import ideal

ORIGIN = (51.4504, 5.6260, 20.0)  # near the A270, Helmond
EPOCH = dt.datetime(2016, 5, 28, 10, 0, 0, tzinfo=dt.timezone.utc)


def _to_geodetic(x_m, y_m, z_m):
    return pymap3d.enu2geodetic(x_m, y_m, z_m, *ORIGIN)


def _flat_to_geodetic(x_m, y_m, z_m):
    """A local tangent-plane approximation, fast enough for thousands of samples."""
    lat0, lon0, alt0 = ORIGIN
    return (lat0 + math.degrees(y_m / 6_378_137.0),
            lon0 + math.degrees(x_m / (6_378_137.0 * math.cos(math.radians(lat0)))), alt0 + z_m)


def _sensor(to_geodetic=_to_geodetic, **config):
    config.setdefault("timing", SensorTimingConfig(rate_hz=10.0))
    return GnssSensor(ideal(GnssConfig(**config)), sensor_rng(7, "ego", "gnss"), to_geodetic, EPOCH)


def _ego(x_m=120.0, y_m=-35.0, heading_rad=0.3, speed_mps=11.0):
    return sim_pb2.VehicleTruth(vehicle_id="ego", x_m=x_m, y_m=y_m, heading_rad=heading_rad, speed_mps=speed_mps)


@pytest.mark.parametrize("mode, quality", [
    (FixModeName.RTK_FIXED, 4), (FixModeName.RTK_FLOAT, 5), (FixModeName.DGPS, 2),
    (FixModeName.SBAS, 9), (FixModeName.SINGLE, 1)])
def test_nmea_sentences_parse_with_valid_checksums_and_the_fix_quality_of_the_mode(mode, quality):
    output = _sensor(fix_mode=mode).poll(0.0, _ego())[0]
    kinds = []
    for raw in output.sentences:
        text = raw.decode("ascii")
        assert text.endswith("\r\n")
        body, given = text.strip()[1:].split("*")
        assert given == checksum(body)
        message = pynmea2.parse(text.strip(), check=True)
        kinds.append(message.sentence_type)
        if message.sentence_type == "GGA":
            assert message.gps_qual == quality
    assert kinds == ["GGA", "RMC", "GST", "VTG"]


def test_a_perfect_receiver_round_trips_the_antenna_position_and_speed():
    ego = _ego()
    output = _sensor(accuracy_scale=0.0, speed_sigma_mps=0.0, course_sigma_deg=0.0).poll(0.0, ego)[0]
    gga = pynmea2.parse(output.sentences[0].decode().strip())
    x_m, y_m, _ = pymap3d.geodetic2enu(gga.latitude, gga.longitude, gga.altitude, *ORIGIN)
    assert x_m == pytest.approx(ego.x_m, abs=0.002)
    assert y_m == pytest.approx(ego.y_m, abs=0.002)
    vtg = pynmea2.parse(output.sentences[3].decode().strip())
    assert vtg.spd_over_grnd_kmph == pytest.approx(ego.speed_mps * 3.6, abs=1e-3)
    assert vtg.true_track == pytest.approx(90.0 - math.degrees(ego.heading_rad), abs=0.01)
    rmc = pynmea2.parse(output.sentences[1].decode().strip())
    assert rmc.datestamp == EPOCH.date() and rmc.status == "A"


def test_position_noise_matches_the_accuracy_of_the_fix_mode():
    sensor = _sensor(_flat_to_geodetic, fix_mode=FixModeName.SINGLE)
    ego = _ego()
    errors = []
    for k in range(2000):
        for output in sensor.poll(k * 0.1, ego):
            errors.append((output.measured_x_m - ego.x_m, output.measured_y_m - ego.y_m))
    errors = np.array(errors)
    assert len(errors) == 2000
    assert np.abs(errors.mean(axis=0)).max() < 0.25
    assert errors.std(axis=0) == pytest.approx([axis_sigma_m(gnss_pb2.FIX_MODE_SINGLE)] * 2, rel=0.08)
    gst = pynmea2.parse(output.sentences[2].decode().strip())
    assert gst.std_dev_latitude == pytest.approx(axis_sigma_m(gnss_pb2.FIX_MODE_SINGLE), abs=1e-3)


def test_an_outage_reports_no_fix_with_empty_position_and_a_downgrade_changes_the_quality():
    sensor = _sensor()
    sensor.set_outage(True)
    gga = pynmea2.parse(sensor.poll(0.0, _ego())[0].sentences[0].decode().strip())
    assert gga.gps_qual == 0 and gga.lat == ""
    sensor.set_outage(False)
    sensor.set_fix_mode(FixModeName.RTK_FLOAT)
    gga = pynmea2.parse(sensor.poll(0.1, _ego())[0].sentences[0].decode().strip())
    assert gga.gps_qual == 5


def test_samples_arrive_after_the_latency_and_dropouts_are_lost():
    sensor = _sensor(_flat_to_geodetic,
                     timing=SensorTimingConfig(rate_hz=10.0, latency_s=0.05, dropout_probability=0.3))
    delivered = []
    for k in range(0, 8000):
        for output in sensor.poll(k * 0.025, _ego()):
            assert output.delivery_time_s - output.sample_time_s == pytest.approx(0.05)
            delivered.append(output)
    assert len(delivered) / 2000 == pytest.approx(0.7, abs=0.03)


def test_an_sbas_fix_can_be_reported_as_quality_2_like_u_blox_receivers():
    output = _sensor(fix_mode=FixModeName.SBAS, sbas_gga_quality=2).poll(0.0, _ego())[0]
    assert pynmea2.parse(output.sentences[0].decode().strip()).gps_qual == 2


def test_the_geolocation_decoder_reads_our_epochs_with_their_fix_mode_and_position():
    decoder_module = pytest.importorskip("coopdrive.gnss.nmea_decoder")
    for mode in FixModeName:
        fixes = []
        decoder = decoder_module.NmeaDecoder(fixes.append)
        output = _sensor(fix_mode=mode, accuracy_scale=0.0).poll(0.0, _ego())[0]
        decoder.feed(output.data, 0.02)
        decoder.flush()
        assert not decoder.bad, decoder.bad
        assert [f.fix_mode for f in fixes] == [mode.proto]
        if mode is not FixModeName.NO_FIX:
            assert (fixes[0].latitude_deg, fixes[0].longitude_deg) == pytest.approx(
                (output.fix.latitude_deg, output.fix.longitude_deg), abs=1e-8)


@settings(max_examples=200, deadline=None)
@given(st.floats(-89.9, 89.9), st.floats(-179.9, 179.9), st.floats(0.0, 100.0))
def test_any_position_and_time_written_as_nmea_reads_back_within_a_millimetre(lat_deg, lon_deg, seconds):
    fix = NmeaFix(utc=EPOCH + dt.timedelta(seconds=seconds), latitude_deg=lat_deg, longitude_deg=lon_deg,
                  altitude_m=12.0, fix_mode=gnss_pb2.FIX_MODE_RTK_FIXED, speed_mps=1.0, course_deg=359.999,
                  std_north_m=0.01, std_east_m=0.01, std_up_m=0.02, satellites=12, hdop=0.8)
    gga = pynmea2.parse(NmeaWriter().gga(fix).decode().strip(), check=True)
    assert float(gga.lat[2:]) < 60.0 and float(gga.lon[3:]) < 60.0
    assert gga.latitude == pytest.approx(lat_deg, abs=1e-8)
    assert gga.longitude == pytest.approx(lon_deg, abs=1e-8)
    written = dt.datetime.combine(EPOCH.date(), gga.timestamp.replace(tzinfo=None))
    # Centiseconds on the wire: half of one, plus the microsecond the datetime itself rounds the time to.
    assert abs((written - EPOCH.replace(tzinfo=None)).total_seconds() - seconds) <= 0.005 + 1e-6


def test_each_epoch_also_comes_as_a_gnss_fix_message_with_its_header():
    sensor = GnssSensor(ideal(GnssConfig(fix_mode=FixModeName.RTK_FLOAT, timing=SensorTimingConfig(rate_hz=10.0,
                                                                                              latency_s=0.03))),
                        sensor_rng(7, "ego", "gnss"), _to_geodetic, EPOCH, vehicle_id="ego")
    outputs = [o for k in range(3) for o in sensor.poll(k * 0.1, _ego())]
    message = outputs[-1].message
    assert message.fix_mode == gnss_pb2.FIX_MODE_RTK_FLOAT
    assert message.latitude_deg == outputs[-1].fix.latitude_deg
    assert message.std_east_m == pytest.approx(axis_sigma_m(gnss_pb2.FIX_MODE_RTK_FLOAT))
    assert (message.header.vehicle_id, message.header.sequence) == ("ego", len(outputs))
    assert message.header.sent_time_s - message.header.sample_time_s == pytest.approx(0.03)
