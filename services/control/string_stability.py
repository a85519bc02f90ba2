"""Frequency-domain string stability of the following laws between two identical consecutive vehicles.

Vehicle: tau a' + a = u(t - phi), i.e. X(s) = G(s) U(s), G = e^{-phi s} / (s^2 (tau s + 1)).
Every law is linear around a steady state and written as
    U = Cp(s) X_p - Cx(s) X + F(s) A_p,     A_p = s^2 X_p e^{-theta s} (V2V) or the radar estimate (dCACC)
so the speed (and position) transfer between vehicle i-1 and i is
    H(s) = V_i / V_{i-1} = (Cp + F A_p / X_p) / (1/G + Cx)                               (eq. SS1)
and, in a homogeneous string, the spacing errors propagate with the same H (E_i / E_{i-1} = H).
String stable iff max_w |H(jw)| <= 1.
    Ploeg:     Cp = (kp + kd s)/(1 + h s),  Cx = Cp (1 + h s),  F = 1/(1 + h s)
               (commanded variant: A_p replaced by the predecessor's delayed input U_p = X_p / G e^{-theta s})
    ours:      Cp = (kp + kd s)/(1 + tau_fb s),  Cx = Cp (1 + h s),  F = (1 + tau s)/(1 + h s)   (eq. C1, C4)
               (commanded variant: F = (1 + lead s)/(1 + h s) on the predecessor's delayed input U_p, eq. C3, C5)
    dCACC:     ours with A_p = s V_p filtered by the least-squares slope FIR (eq. D1), no V2V delay
    Rajamani:  Cp = (lambda + s)/h,         Cx = (lambda (1 + h s) + s)/h,  F = 0
    our ACC:   Cp = ke + kv s,              Cx = ke (1 + h s) + kv s + ka h s^2,  F = 0

Where Cx = Cp (1 + h s) and the feed-forward is the ideal one times a factor rho, F A_p / X_p = rho / (G (1 + h s))
(ours fed the request: rho = (1 + lead s) e^{-theta s}; Ploeg fed it: rho = e^{-theta s}), SS1 is
    H(s) = (1 / (1 + h s)) (L + rho) / (1 + L),     L = Cp (1 + h s) G                   (eq. SS2)
so rho = 1 gives the ideal time-gap transfer 1 / (1 + h s) whatever the feedback, and the feedback only weighs
rho's error: H / H_ideal = 1 - (1 - rho) / (1 + L). For the car (plant lag 0.5 s, dead time 0.1 s) and our gains,
1 / (1 + L) = 0.06 + 0.56 j at 0.2 Hz: a phase lag eps of rho raises |H| by about 0.56 eps, its size hardly
counts. A lead shorter than the request's age theta leaves eps = w (theta - lead): 0.6 % of |H| per 0.01 s.
"""

from __future__ import annotations

import enum
from dataclasses import dataclass
from pathlib import Path

import numpy as np

from coopdrive.vehicle import SPACING

from .profiles import VehicleProfile

DEFAULT_COMM_DELAY_S = 0.1
STRING_STABLE_TOLERANCE = 1e-6
ESTIMATOR_SAMPLE_S = 0.02
DEFAULT_OMEGA_RADPS = np.logspace(-3, 1.5, 2000)


class FollowingLaw(enum.Enum):
    OURS_CACC = "ours_cacc"
    PLOEG_CACC = "ploeg_cacc"
    # Ploeg fed the predecessor's *commanded* acceleration (iCLCM targetLongitudinalAcceleration), as in his paper.
    PLOEG_CACC_COMMANDED = "ploeg_cacc_commanded"
    # Ours fed the predecessor's commanded acceleration (eq. C3), what it runs on when the iCLCM is fresh.
    OURS_CACC_COMMANDED = "ours_cacc_commanded"
    DCACC = "dcacc"
    OURS_ACC = "ours_acc"
    RAJAMANI_ACC = "rajamani_acc"


@dataclass(frozen=True)
class StringStabilityResult:
    law: FollowingLaw
    profile_name: str
    time_gap_s: float
    engine_lag_s: float
    actuation_delay_s: float
    comm_delay_s: float
    omega_radps: np.ndarray
    speed_gain: np.ndarray
    # |E / V_p|, spacing error per unit predecessor speed oscillation, s.
    spacing_error_gain_s: np.ndarray

    @property
    def max_speed_gain(self) -> float:
        return float(self.speed_gain.max())

    @property
    def peak_omega_radps(self) -> float:
        return float(self.omega_radps[int(self.speed_gain.argmax())])

    @property
    def string_stable(self) -> bool:
        return self.max_speed_gain <= 1.0 + STRING_STABLE_TOLERANCE

    def gain_at_hz(self, frequency_hz: float) -> float:
        return float(np.interp(2 * np.pi * frequency_hz, self.omega_radps, self.speed_gain))


def _slope_fir(s: np.ndarray, window_s: float) -> np.ndarray:
    """Frequency response of the least-squares slope estimator (eq. D1) on samples ESTIMATOR_SAMPLE_S apart."""
    n = int(round(window_s / ESTIMATOR_SAMPLE_S)) + 1
    ages = np.arange(n) * ESTIMATOR_SAMPLE_S
    centred = -ages - (-ages).mean()
    coeffs = centred / np.sum(centred**2)
    return sum(c * np.exp(-s * age) for c, age in zip(coeffs, ages))


def speed_transfer(
    law: FollowingLaw,
    profile: VehicleProfile,
    time_gap_s: float,
    omega_radps: np.ndarray,
    comm_delay_s: float = DEFAULT_COMM_DELAY_S,
    engine_lag_s: float | None = None,
    actuation_delay_s: float | None = None,
) -> np.ndarray:
    """H(jw) = V_i / V_{i-1} (eq. SS1). The plant lag/delay default to the profile's; the law uses the profile's lag."""
    s = 1j * np.asarray(omega_radps, dtype=float)
    h = time_gap_s
    tau = profile.engine_lag_s if engine_lag_s is None else engine_lag_s
    phi = profile.actuation_delay_s if actuation_delay_s is None else actuation_delay_s
    inv_plant = s**2 * (tau * s + 1) * np.exp(phi * s)
    v2v_accel = s**2 * np.exp(-comm_delay_s * s)
    # The predecessor's input as received: U_p = X_p / G, sent comm_delay_s later.
    v2v_command = inv_plant * np.exp(-comm_delay_s * s)
    ff = np.zeros_like(s)
    if law in (FollowingLaw.PLOEG_CACC, FollowingLaw.PLOEG_CACC_COMMANDED):
        g = profile.ploeg
        cp = (g.kp_1ps2 + g.kd_1ps * s) / (1 + h * s)
        cx = cp * (1 + h * s)
        sent = v2v_accel if law is FollowingLaw.PLOEG_CACC else v2v_command
        ff = sent / (1 + h * s)
    elif law in (FollowingLaw.OURS_CACC, FollowingLaw.OURS_CACC_COMMANDED, FollowingLaw.DCACC):
        g = profile.cacc
        cp = (g.kp_1ps2 + g.kd_1ps * s) / (1 + g.feedback_time_constant_s * s)
        cx = cp * (1 + h * s)
        if law is FollowingLaw.OURS_CACC_COMMANDED:
            ff = v2v_command * (1 + g.request_lead_s * s) / (1 + h * s)
        else:
            accel = v2v_accel if law is FollowingLaw.OURS_CACC else s * _slope_fir(s, profile.dcacc.estimator_window_s)
            ff = accel * (1 + profile.engine_lag_s * s) / (1 + h * s)
    elif law is FollowingLaw.RAJAMANI_ACC:
        lam = profile.rajamani.lambda_1ps
        cp = (lam + s) / h
        cx = (lam * (1 + h * s) + s) / h
    elif law is FollowingLaw.OURS_ACC:
        g = profile.acc
        cp = g.ke_1ps2 + g.kv_1ps * s
        cx = g.ke_1ps2 * (1 + h * s) + g.kv_1ps * s + g.ka * h * s**2
    else:
        raise ValueError(f"unknown following law {law!r}")
    return (cp + ff) / (inv_plant + cx)


def analyze(
    law: FollowingLaw,
    profile: VehicleProfile,
    time_gap_s: float | None = None,
    comm_delay_s: float = DEFAULT_COMM_DELAY_S,
    engine_lag_s: float | None = None,
    actuation_delay_s: float | None = None,
    omega_radps: np.ndarray = DEFAULT_OMEGA_RADPS,
) -> StringStabilityResult:
    # By default the gap the runs drive: the CACC gap the planner requests.
    h = SPACING.cacc_time_gap_s if time_gap_s is None else time_gap_s
    hv = speed_transfer(law, profile, h, omega_radps, comm_delay_s, engine_lag_s, actuation_delay_s)
    s = 1j * omega_radps
    # E = X_p - (1 + h s) X  =>  E / V_p = (1 - (1 + h s) H) / s
    spacing = np.abs((1 - (1 + h * s) * hv) / s)
    return StringStabilityResult(
        law=law,
        profile_name=profile.name,
        time_gap_s=h,
        engine_lag_s=profile.engine_lag_s if engine_lag_s is None else engine_lag_s,
        actuation_delay_s=profile.actuation_delay_s if actuation_delay_s is None else actuation_delay_s,
        comm_delay_s=comm_delay_s,
        omega_radps=np.asarray(omega_radps),
        speed_gain=np.abs(hv),
        spacing_error_gain_s=spacing,
    )


def plot(results: list[StringStabilityResult], path: str | Path, title: str = "String stability") -> Path:
    """Bode magnitude of V_i / V_{i-1} for each result, saved as an image (Agg backend, no display)."""
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    fig, (ax_v, ax_e) = plt.subplots(2, 1, figsize=(8, 7), sharex=True)
    for r in results:
        label = f"{r.law.value} h={r.time_gap_s:.2f} s tau={r.engine_lag_s:.2f} s (max {r.max_speed_gain:.3f})"
        freq_hz = r.omega_radps / (2 * np.pi)
        ax_v.semilogx(freq_hz, 20 * np.log10(r.speed_gain), label=label)
        ax_e.semilogx(freq_hz, r.spacing_error_gain_s, label=label)
    ax_v.axhline(0.0, color="k", linewidth=0.8, linestyle="--")
    ax_v.set_ylabel("|V_i / V_i-1| [dB]")
    ax_e.set_ylabel("|E_i / V_i-1| [s]")
    ax_e.set_xlabel("frequency [Hz]")
    ax_v.set_title(title)
    ax_v.legend(fontsize=7)
    for ax in (ax_v, ax_e):
        ax.grid(True, which="both", alpha=0.3)
    path = Path(path)
    fig.tight_layout()
    fig.savefig(path, dpi=120)
    plt.close(fig)
    return path
