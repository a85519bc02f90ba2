import math

from hypothesis import given
from hypothesis import strategies as st

from coopdrive.v2x import units


def test_latitude_in_degrees_becomes_tenths_of_microdegrees():
    assert units.LATITUDE_TENTH_MICRODEG.to_wire(57.7089) == 577_089_000
    assert units.LATITUDE_TENTH_MICRODEG.to_si(-577_089_000) == -57.7089


def test_values_beyond_a_field_range_are_clamped_to_its_limits():
    assert units.SPEED_CMPS.to_wire(500.0) == 16_382
    assert units.SPEED_CMPS.to_wire(-3.0) == 0
    assert units.LATITUDE_TENTH_MICRODEG.to_wire(91.0) == 900_000_000
    assert units.ICLCM_TARGET_ACCELERATION_CMPS2.to_wire(-25.0) == -1000


def test_none_and_nan_become_the_unavailable_code_and_back_to_none():
    assert units.SPEED_CMPS.to_wire(None) == 16_383
    assert units.ALTITUDE_CM.to_wire(float("nan")) == 800_001
    assert units.SPEED_CMPS.to_si(16_383) is None
    assert units.ICLCM_TIME_HEADWAY_100MS.to_si(361) is None


def test_a_confidence_beyond_its_range_is_out_of_range_and_decodes_as_infinity():
    assert units.SPEED_CONFIDENCE_CMPS.to_wire(2.0) == 126
    assert units.SPEED_CONFIDENCE_CMPS.to_si(126) == math.inf
    assert units.ALTITUDE_CONFIDENCE.to_wire(0.3) == "alt-000-50"
    assert units.ALTITUDE_CONFIDENCE.to_wire(300.0) == "outOfRange"
    assert units.ALTITUDE_CONFIDENCE.to_si("outOfRange") == math.inf


def test_east_in_enu_is_900_tenths_of_a_degree_in_etsi_and_north_is_zero():
    assert units.heading_enu_rad_to_etsi_tenth_deg(0.0) == 900
    assert units.heading_enu_rad_to_etsi_tenth_deg(math.pi / 2) == 0
    assert units.heading_enu_rad_to_etsi_tenth_deg(-math.pi / 2) == 1800
    assert units.heading_enu_rad_to_etsi_tenth_deg(math.pi) == 2700
    assert units.etsi_tenth_deg_to_heading_enu_rad(2700) == math.pi
    assert units.etsi_tenth_deg_to_heading_enu_rad(3601) is None


@given(st.floats(min_value=-math.pi, max_value=math.pi))
def test_a_heading_survives_the_etsi_round_trip_within_a_tenth_of_a_degree(heading_rad):
    back = units.etsi_tenth_deg_to_heading_enu_rad(units.heading_enu_rad_to_etsi_tenth_deg(heading_rad))
    assert abs(math.remainder(back - heading_rad, math.tau)) <= math.radians(0.05) + 1e-12


def test_curvature_units_differ_between_the_v1_and_v2_dictionaries():
    assert units.CURVATURE_V1_PER_30000M.to_wire(0.01) == 300
    assert units.CURVATURE_V2_PER_10000M.to_wire(0.01) == 100


def test_mio_bearing_to_the_left_is_positive_in_the_stack_and_negative_on_the_wire():
    assert units.ICLCM_MIO_BEARING_2MRAD_RIGHT.to_wire(0.5) == -250
    assert units.ICLCM_MIO_BEARING_2MRAD_RIGHT.to_si(-250) == 0.5
    assert units.ICLCM_MIO_BEARING_2MRAD_RIGHT.to_wire(math.inf) == -1571


def test_iclcm_units_are_centimetres_hundredths_and_tenths_of_seconds():
    assert units.ICLCM_REAR_AXLE_LOCATION_CM.to_wire(4.2) == 420
    assert units.ICLCM_RESPONSE_TIME_10MS.to_wire(0.5) == 50
    assert units.ICLCM_TIME_HEADWAY_100MS.to_wire(0.5) == 5
    assert units.ICLCM_CRUISE_SPEED_CMPS.to_wire(22.22) == 2222
