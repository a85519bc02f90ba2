"""The GNSS antenna's lever arm comes from the car's file (vehicle CAN adapter, mounting.gnss_antenna) unless the
geolocator's keys set it, and a fix's noise by quality is a setting (geolocator.gnss_fix_std_m)."""

import shutil

import pytest

from coopdrive.services.geolocation.config import DEFAULT_ANTENNA_X_M, GeolocationConfig, GeolocatorConfig
from coopdrive.services.geolocation.ekf import FIX_MODE_STD_M
from coopdrive.services.geolocation.geolocator import Geolocator
from coopdrive.v1 import gnss_pb2
from tests.can.rav4_drive import RAV4_ADAPTER

ORIGIN = (37.72, -122.47, 0.0)


def car_file(tmp_path, antenna: str):
    """The RAV4's adapter with its mounting replaced, beside a copy of its DBC."""
    shutil.copy(RAV4_ADAPTER.parent / "opendbc_toyota_new_mc_pt_generated.dbc", tmp_path)
    text = RAV4_ADAPTER.read_text().replace("gnss_antenna: {x_m: 1.0, y_m: 0.0}", antenna)
    path = tmp_path / "car.yaml"
    path.write_text(text)
    return str(path)


def test_the_antenna_comes_from_the_car_s_file_and_the_geolocator_keys_win_over_it(tmp_path):
    path = car_file(tmp_path, "gnss_antenna: {x_m: 1.7, y_m: -0.3}")
    assert GeolocationConfig(vehicle_can=path).antenna_m() == (1.7, -0.3)
    assert GeolocationConfig(vehicle_can=path, geolocator={"antenna_x_m": 0.5}).antenna_m() == (0.5, -0.3)
    assert GeolocationConfig().antenna_m() == (DEFAULT_ANTENNA_X_M, 0.0)


def test_a_car_s_file_with_an_antenna_but_no_x_is_refused_naming_the_field(tmp_path):
    path = car_file(tmp_path, "gnss_antenna: {y_m: 0.2}")
    with pytest.raises(ValueError, match="x_m"):
        GeolocationConfig(vehicle_can=path).antenna_m()


def test_a_quality_1_fix_without_gst_is_taken_with_the_configured_noise_not_the_table_s_5_m():
    assert FIX_MODE_STD_M[gnss_pb2.FIX_MODE_SINGLE] == GeolocatorConfig().gnss_fix_std_m.single_m == 5.0
    geolocator = Geolocator(GeolocatorConfig(gnss_fix_std_m={"single_m": 1.5}), origin=ORIGIN)
    fix = gnss_pb2.GnssFix(latitude_deg=37.72, longitude_deg=-122.47, fix_mode=gnss_pb2.FIX_MODE_SINGLE)
    fix.header.sample_time_s = 100.0
    geolocator.on_gnss_fix(fix)
    correlated_var = GeolocatorConfig().gnss_error_std_m**2
    assert geolocator.ekf.P[0, 0] == pytest.approx(1.5**2 + DEFAULT_ANTENNA_X_M**2 / 2.0 + correlated_var)
