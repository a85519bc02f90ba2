"""Frequency-domain string stability of the following laws (eq. SS1)."""

import numpy as np
import pytest

from coopdrive.services.control.profiles import CAR, TRUCK
from coopdrive.services.control.string_stability import FollowingLaw, analyze, plot, speed_transfer

TIME_GAPS_S = [0.5, 0.7, 1.0]
LAGS_S = [0.1, 0.3, 0.5]


def with_lag(lag_s):
    return CAR.with_driveline(lag_s=lag_s)


@pytest.mark.parametrize("time_gap_s", TIME_GAPS_S)
@pytest.mark.parametrize("lag_s", LAGS_S)
def test_our_cacc_is_string_stable_with_lag_dead_time_and_v2v_delay(time_gap_s, lag_s):
    result = analyze(FollowingLaw.OURS_CACC, with_lag(lag_s), time_gap_s, comm_delay_s=0.1)
    assert result.string_stable, f"max |H| = {result.max_speed_gain:.4f}"


@pytest.mark.parametrize("time_gap_s", TIME_GAPS_S)
@pytest.mark.parametrize("lag_s", LAGS_S)
def test_our_cacc_damps_at_least_as_well_as_ploeg_at_the_same_time_gap(time_gap_s, lag_s):
    ours = analyze(FollowingLaw.OURS_CACC, with_lag(lag_s), time_gap_s)
    ploeg = analyze(FollowingLaw.PLOEG_CACC, with_lag(lag_s), time_gap_s)
    assert ours.max_speed_gain <= ploeg.max_speed_gain + 1e-9
    assert ours.gain_at_hz(0.2) <= ploeg.gain_at_hz(0.2)


@pytest.mark.parametrize("dead_time_s", [0.05, 0.1])
@pytest.mark.parametrize("time_gap_s", TIME_GAPS_S)
@pytest.mark.parametrize("lag_s", LAGS_S)
def test_fed_the_predecessors_command_as_ploeg_is_ours_damps_no_worse(time_gap_s, lag_s, dead_time_s):
    # The fair comparison when the iCLCM request is fresh: both laws feed forward the same delayed command.
    profile = with_lag(lag_s).with_driveline(dead_time_s=dead_time_s)
    ours = analyze(FollowingLaw.OURS_CACC_COMMANDED, profile, time_gap_s)
    ploeg = analyze(FollowingLaw.PLOEG_CACC_COMMANDED, profile, time_gap_s)
    assert ours.max_speed_gain <= ploeg.max_speed_gain + 1e-9
    assert ours.gain_at_hz(0.2) <= ploeg.gain_at_hz(0.2)


def without_request_lead(profile):
    return profile.model_copy(update={"cacc": profile.cacc.model_copy(update={"request_lead_s": 0.0})})


def test_without_delays_our_cacc_fed_the_command_is_the_ideal_transfer_for_any_lag():
    omega = np.array([0.1, 1.0, 5.0])
    profile = without_request_lead(with_lag(0.5).with_driveline(dead_time_s=0.0))
    h = speed_transfer(FollowingLaw.OURS_CACC_COMMANDED, profile, 0.5, omega, comm_delay_s=0.0)
    assert np.abs(h) == pytest.approx(1 / np.sqrt(1 + (0.5 * omega) ** 2))


# The request's age at our control in the simulated platoons (profiles.CaccGains.request_lead_s): 0.10 s to the
# scene, and the 50 Hz control's wait for the 25 Hz scene.
REQUEST_AGE_S = 0.12


def test_a_request_lead_as_long_as_the_requests_age_nearly_restores_the_ideal_transfer():
    wave = np.array([2 * np.pi * 0.2])  # the string scenario's 0.2 Hz
    profile = with_lag(0.5).with_driveline(dead_time_s=0.0)
    ideal = 1 / np.sqrt(1 + (0.5 * wave) ** 2)
    led = np.abs(speed_transfer(FollowingLaw.OURS_CACC_COMMANDED, profile, 0.5, wave, comm_delay_s=REQUEST_AGE_S))
    late = np.abs(speed_transfer(FollowingLaw.OURS_CACC_COMMANDED, without_request_lead(profile), 0.5, wave,
                                 comm_delay_s=REQUEST_AGE_S))
    assert profile.cacc.request_lead_s == pytest.approx(REQUEST_AGE_S)
    assert abs(led - ideal)[0] < 0.25 * abs(late - ideal)[0]


def test_fed_the_request_the_string_gain_is_the_ideal_times_the_feedforwards_error_through_the_loop():
    # eq. SS2: H = (1 / (1 + h s)) (L + rho) / (1 + L), L = Cp (1 + h s) G, rho = (1 + lead s) e^{-theta s}
    omega = np.array([0.3, 2 * np.pi * 0.2, 3.0])
    s, h, lag, dead, age = 1j * omega, 0.5, 0.5, 0.1, 0.12
    gains = CAR.cacc
    plant = np.exp(-dead * s) / (s**2 * (1 + lag * s))
    loop = (gains.kp_1ps2 + gains.kd_1ps * s) / (1 + gains.feedback_time_constant_s * s) * (1 + h * s) * plant
    rho = (1 + gains.request_lead_s * s) * np.exp(-age * s)
    expected = (loop + rho) / (1 + loop) / (1 + h * s)
    h_ours = speed_transfer(FollowingLaw.OURS_CACC_COMMANDED, CAR, h, omega, comm_delay_s=age, engine_lag_s=lag,
                            actuation_delay_s=dead)
    assert h_ours == pytest.approx(expected)


def test_at_the_wave_frequency_a_lead_short_of_the_requests_age_raises_the_string_gain():
    # eq. SS2: at 0.2 Hz 1 / (1 + L) is nearly imaginary, so rho's phase lag w (theta - lead) counts, its size not.
    def gain(lead_s):
        profile = CAR.model_copy(update={"cacc": CAR.cacc.model_copy(update={"request_lead_s": lead_s})})
        return analyze(FollowingLaw.OURS_CACC_COMMANDED, profile, 0.5, comm_delay_s=REQUEST_AGE_S, engine_lag_s=0.5,
                       actuation_delay_s=0.1).gain_at_hz(0.2)

    ideal = 1 / np.sqrt(1 + (0.5 * 2 * np.pi * 0.2) ** 2)
    assert gain(REQUEST_AGE_S) == pytest.approx(ideal, abs=0.002)
    assert gain(REQUEST_AGE_S - 0.02) - gain(REQUEST_AGE_S) == pytest.approx(0.012, abs=0.002)


def test_without_delays_ploeg_fed_the_command_is_the_ideal_transfer_for_any_lag():
    omega = np.array([0.1, 1.0, 5.0])
    profile = with_lag(0.5).with_driveline(dead_time_s=0.0)
    h = speed_transfer(FollowingLaw.PLOEG_CACC_COMMANDED, profile, 0.5, omega, comm_delay_s=0.0)
    assert np.abs(h) == pytest.approx(1 / np.sqrt(1 + (0.5 * omega) ** 2))


def test_without_delays_our_cacc_is_exactly_the_ideal_time_gap_transfer():
    omega = np.array([0.1, 1.0, 2 * np.pi * 0.2, 5.0])
    profile = with_lag(0.4).with_driveline(dead_time_s=0.0)
    h = speed_transfer(FollowingLaw.OURS_CACC, profile, 0.5, omega, comm_delay_s=0.0)
    assert np.abs(h) == pytest.approx(1 / np.sqrt(1 + (0.5 * omega) ** 2))


def test_ploeg_fed_its_predecessors_command_without_lag_is_the_ideal_transfer_too():
    omega = np.array([0.1, 1.0, 5.0])
    profile = with_lag(1e-9).with_driveline(dead_time_s=0.0)
    h = speed_transfer(FollowingLaw.PLOEG_CACC, profile, 0.5, omega, comm_delay_s=0.0)
    assert np.abs(h) == pytest.approx(1 / np.sqrt(1 + (0.5 * omega) ** 2), rel=1e-6)


def test_ploeg_fed_the_measured_acceleration_amplifies_at_half_a_second_with_lag():
    assert not analyze(FollowingLaw.PLOEG_CACC, with_lag(0.3), 0.5).string_stable


@pytest.mark.parametrize("lag_s", LAGS_S)
def test_the_fallbacks_are_string_stable_at_their_raised_time_gaps(lag_s):
    profile = with_lag(lag_s)
    assert analyze(FollowingLaw.DCACC, profile, profile.spacing.dcacc_time_gap_s).string_stable
    assert analyze(FollowingLaw.OURS_ACC, profile, profile.spacing.acc_time_gap_s).string_stable
    assert analyze(FollowingLaw.RAJAMANI_ACC, profile, profile.spacing.acc_time_gap_s).string_stable


def test_the_truck_profile_is_string_stable_at_its_default_time_gap():
    assert analyze(FollowingLaw.OURS_CACC, TRUCK).string_stable


def test_the_spacing_error_gain_vanishes_at_low_frequency_for_the_cooperative_law():
    result = analyze(FollowingLaw.OURS_CACC, CAR, 0.5)
    assert result.spacing_error_gain_s[0] < 1e-2


def test_the_plot_is_written_as_an_image(tmp_path):
    results = [analyze(law, CAR, 0.5) for law in (FollowingLaw.OURS_CACC, FollowingLaw.PLOEG_CACC)]
    path = plot(results, tmp_path / "string.png")
    assert path.exists() and path.stat().st_size > 1000
