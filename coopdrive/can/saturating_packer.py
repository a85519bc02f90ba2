"""SaturatingPacker: one DBC frame's signals to its payload bytes, each value saturated at its DBC range first.

The simulator puts about 480 frames a second per vehicle on its buses, and cantools' general encoder (any byte
order, multiplexing, choices, range checks) took a sixth of the simulator's CPU. This packer is the narrow case
the simulator needs, worked out once per frame from the cantools definition: Intel (little-endian) integer
signals without multiplexing, each value converted by the signal's own cantools conversion (so rounding is
cantools') and placed at its start bit. A frame outside that case is refused when the packer is made, and its
payload is the one cantools would encode from the saturated values (tests/can/test_saturating_packer.py).
"""

from __future__ import annotations

from collections.abc import Mapping

from cantools.database.can import Message


class SaturatingPacker:
    def __init__(self, definition: Message):
        if definition.is_multiplexed() or definition.is_container:
            raise ValueError(f"{definition.name}: multiplexed and container frames are not packed here")
        self.length = definition.length
        self._signals = []
        for signal in definition.signals:
            if signal.byte_order != "little_endian" or signal.conversion.is_float:
                raise ValueError(f"{definition.name}.{signal.name}: only little-endian integer signals are packed here")
            self._signals.append((signal.name, signal.minimum, signal.maximum, signal.conversion.numeric_scaled_to_raw,
                                  (1 << signal.length) - 1, signal.start))

    def pack(self, values: Mapping[str, float]) -> bytearray:
        """The payload; every signal must be given. A value beyond the DBC range takes the range's end, NaN its
        minimum (0 where the DBC gives none): a simulated sensor may read what the wire cannot carry."""
        payload = 0
        for name, low, high, to_raw, mask, start in self._signals:
            value = values[name]
            if value != value:  # NaN
                value = low if low is not None else 0.0
            if low is not None and value < low:
                value = low
            if high is not None and value > high:
                value = high
            # Two's complement of a signed raw value falls out of the mask.
            payload |= (to_raw(value) & mask) << start
        return bytearray(payload.to_bytes(self.length, "little"))


def saturated_values(definition: Message, values: Mapping[str, float]) -> dict[str, float]:
    """What SaturatingPacker.pack means, in plain terms: each value at its DBC range's end if beyond it, NaN at the
    minimum (0 where the DBC gives none). The packer's payload is cantools' encoding of these values."""
    out = {}
    for signal in definition.signals:
        value = values[signal.name]
        if value != value:  # NaN
            value = signal.minimum if signal.minimum is not None else 0.0
        if signal.minimum is not None:
            value = max(value, signal.minimum)
        if signal.maximum is not None:
            value = min(value, signal.maximum)
        out[signal.name] = value
    return out
