"""Where a vehicle is: VehicleTruth.x_m / y_m and the ego frame are at the centre of the rear axle, and a vehicle that
does not say how far its rear bumper sits behind that axle is drawn and judged with a typical overhang."""

# Rear axle to rear bumper as a share of the length when a vehicle does not say (typical cars and trucks).
DEFAULT_REAR_OVERHANG_RATIO = 0.2


def rear_overhang_m(length_m: float) -> float:
    return DEFAULT_REAR_OVERHANG_RATIO * length_m
