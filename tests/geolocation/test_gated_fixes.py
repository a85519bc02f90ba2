from coopdrive.services.geolocation.gated_fixes import GatedFixes


def _since_s(offsets, fix_std_m=0.01, floor_m=0.5):
    fixes = GatedFixes(0.0, offsets[0])
    for k, offset in enumerate(offsets[1:], start=1):
        fixes = fixes.with_fix(0.05 * k, offset, fix_std_m, floor_m)
    return fixes.since_s


def test_refused_fixes_moving_smoothly_against_a_drifting_filter_count_from_the_first():
    drifting = [(3.0 + 0.01 * k, 4.0 - 0.02 * k) for k in range(60)]
    assert _since_s(drifting) == 0.0


def test_a_multipath_step_between_refused_fixes_starts_the_count_again():
    jumping = [(3.0, 0.0)] * 20 + [(-1.0, 2.5)] * 20 + [(0.5, -3.0)] * 20
    assert _since_s(jumping) == 0.05 * 40


def test_the_step_allowed_grows_with_the_noise_the_receiver_reports():
    offsets = [(0.0, 0.0), (1.0, 0.5), (0.0, 1.0)]
    assert _since_s(offsets, fix_std_m=0.01) == 0.1
    assert _since_s(offsets, fix_std_m=1.0) == 0.0
