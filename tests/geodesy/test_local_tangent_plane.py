"""LocalTangentPlane agrees with pymap3d to well below a millimetre over the span of a test track."""

import math

import pymap3d
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from coopdrive.geodesy import LocalTangentPlane

HELMOND = (51.4546, 5.6224, 15.0)
offsets_m = st.floats(min_value=-20_000, max_value=20_000, allow_nan=False)
heights_m = st.floats(min_value=-100, max_value=500, allow_nan=False)


@settings(max_examples=300, deadline=None)
@given(offsets_m, offsets_m, heights_m)
def test_enu_to_geodetic_matches_pymap3d_within_a_tenth_of_a_millimetre(east_m, north_m, up_m):
    expected = pymap3d.enu2geodetic(east_m, north_m, up_m, *HELMOND)
    lat_deg, lon_deg, alt_m = LocalTangentPlane(*HELMOND).to_geodetic(east_m, north_m, up_m)
    metres_per_deg = 111_320.0
    assert abs(lat_deg - expected[0]) * metres_per_deg < 1e-4
    assert abs(lon_deg - expected[1]) * metres_per_deg * math.cos(math.radians(HELMOND[0])) < 1e-4
    assert alt_m == pytest.approx(float(expected[2]), abs=1e-4)


@settings(max_examples=300, deadline=None)
@given(offsets_m, offsets_m, heights_m)
def test_geodetic_to_enu_inverts_to_geodetic(east_m, north_m, up_m):
    plane = LocalTangentPlane(*HELMOND)
    back = plane.to_enu(*plane.to_geodetic(east_m, north_m, up_m))
    assert back == pytest.approx((east_m, north_m, up_m), abs=1e-4)


def test_the_origin_maps_to_zero_and_north_is_north():
    plane = LocalTangentPlane(*HELMOND)
    assert plane.to_enu(*HELMOND) == pytest.approx((0.0, 0.0, 0.0), abs=1e-6)
    east_m, north_m, _ = plane.to_enu(HELMOND[0] + 0.001, HELMOND[1], HELMOND[2])
    assert north_m == pytest.approx(111.26, abs=0.05) and abs(east_m) < 1e-6


@pytest.mark.parametrize("origin", [(0.0, 0.0, 0.0), (-33.9, 151.2, 40.0), (78.2, 15.6, 0.0)])
def test_agrees_with_pymap3d_at_other_origins(origin):
    expected = pymap3d.geodetic2enu(origin[0] + 0.01, origin[1] - 0.02, origin[2] + 3.0, *origin)
    assert LocalTangentPlane(*origin).to_enu(origin[0] + 0.01, origin[1] - 0.02, origin[2] + 3.0) == \
        pytest.approx(tuple(float(v) for v in expected), abs=1e-5)
