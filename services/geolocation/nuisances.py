"""What the geolocation filter learns of its inputs beside the vehicle's state, for diagnostics and a replay's
counters (coopdrive/recording/replay_counts.py prints each with its std)."""

from __future__ import annotations

import math

from coopdrive.recording.replay_counts import ESTIMATED_PREFIX, STD_SUFFIX
from coopdrive.services.geolocation.ekf import GeolocationEkf
from coopdrive.services.geolocation.motion_models import GNSS_TIME_ERROR
from coopdrive.services.geolocation.wheel_scale import WheelScaleEstimator

# Counter names, in the replay's convention for an estimated value (its std under the name + STD_SUFFIX); names
# say the unit.
ESTIMATED_FIX_STAMP_LATE_MS = f"{ESTIMATED_PREFIX}fix_stamp_late_ms"
ESTIMATED_WHEEL_SCALE = f"{ESTIMATED_PREFIX}wheel_scale"


def estimated_nuisances(ekf: GeolocationEkf, time_error_std_s: float,
                        wheel_scale: WheelScaleEstimator | None) -> dict[str, float]:
    """How late the fixes are stamped against the other inputs (the stamp-error state, when it is modelled:
    time_error_std_s > 0), and the wheels' scale (when it is estimated), each with its std."""
    found: dict[str, float] = {}
    if ekf.initialised and time_error_std_s > 0.0:
        found[ESTIMATED_FIX_STAMP_LATE_MS] = 1000.0 * float(ekf.x[GNSS_TIME_ERROR])
        found[ESTIMATED_FIX_STAMP_LATE_MS + STD_SUFFIX] = 1000.0 * math.sqrt(float(ekf.P[GNSS_TIME_ERROR,
                                                                                            GNSS_TIME_ERROR]))
    if wheel_scale is not None:
        found[ESTIMATED_WHEEL_SCALE] = wheel_scale.scale
        found[ESTIMATED_WHEEL_SCALE + STD_SUFFIX] = wheel_scale.std
    return found
