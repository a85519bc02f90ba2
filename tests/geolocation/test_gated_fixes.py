from coopdrive.services.geolocation.gated_fixes import GatedFixes


def _gated(*offsets):
    fixes = GatedFixes(0.0, ())
    for offset in offsets:
        fixes = fixes.with_fix(offset)
    return fixes


def test_refused_fixes_off_by_one_offset_agree_so_the_filter_is_what_drifted():
    assert _gated((3.0, 4.0), (3.02, 3.99), (2.98, 4.01)).consistent(fix_std_m=0.01, floor_m=0.5)


def test_refused_fixes_jumping_about_disagree_so_the_receiver_is_in_multipath():
    assert not _gated((3.0, 0.0), (-1.0, 2.5), (0.5, -3.0)).consistent(fix_std_m=0.01, floor_m=0.5)


def test_the_agreement_allows_for_the_noise_the_receiver_reports():
    jumpy = _gated((1.0, 0.0), (-1.0, 0.5), (0.0, -1.0))
    assert not jumpy.consistent(fix_std_m=0.01, floor_m=0.5)
    assert jumpy.consistent(fix_std_m=1.0, floor_m=0.5)
