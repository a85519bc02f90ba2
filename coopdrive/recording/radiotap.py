"""The radiotap header of a monitor-interface capture, read as radiotap.org defines it, for what decides how the
802.11 frame behind it is read: the header's length, and its Flags field (whether the frame still ends in its
4-byte FCS, whether that FCS was bad, whether the 802.11 header is padded to 32 bits).

The header is `version (u8, 0), pad (u8), length (u16 LE), present (u32 LE)...`: while bit 31 of a present word is
set another word follows. Fields follow the present words in bit order, each aligned to its own size from the
header's start. Flags is bit 1 of the first word; only TSFT (bit 0, a u64 aligned to 8) can come before it.
"""

from __future__ import annotations

import struct
from dataclasses import dataclass

RADIOTAP_VERSION = 0
HEADER = struct.Struct("<BBHI")  # version, pad, length, first present word
PRESENT_WORD = struct.Struct("<I")
PRESENT_EXTENDED_BIT = 1 << 31
PRESENT_TSFT_BIT = 1 << 0
PRESENT_FLAGS_BIT = 1 << 1
TSFT_BYTES = 8

# Flags field bits (radiotap.org/fields/Flags).
FLAG_DATA_PADDED = 0x20
FLAG_FCS_AT_END = 0x10
FLAG_BAD_FCS = 0x40
FCS_BYTES = 4


class RadiotapError(ValueError):
    """A radiotap header that is cut or says it is longer than the frame."""


@dataclass(frozen=True)
class RadiotapHeader:
    length: int
    flags: int

    @property
    def has_fcs(self) -> bool:
        return bool(self.flags & FLAG_FCS_AT_END)

    @property
    def bad_fcs(self) -> bool:
        return bool(self.flags & FLAG_BAD_FCS)

    @property
    def data_padded(self) -> bool:
        return bool(self.flags & FLAG_DATA_PADDED)


def read_radiotap(data: bytes) -> RadiotapHeader:
    if len(data) < HEADER.size:
        raise RadiotapError(f"radiotap header cut at {len(data)} bytes")
    version, _, length, present = HEADER.unpack_from(data)
    if version != RADIOTAP_VERSION:
        raise RadiotapError(f"radiotap version {version}")
    if length < HEADER.size or length > len(data):
        raise RadiotapError(f"radiotap length {length} in a frame of {len(data)} bytes")
    first_present = present
    offset = HEADER.size
    while present & PRESENT_EXTENDED_BIT:
        if offset + PRESENT_WORD.size > length:
            raise RadiotapError("radiotap present words run past the header")
        (present,) = PRESENT_WORD.unpack_from(data, offset)
        offset += PRESENT_WORD.size
    flags = 0
    if first_present & PRESENT_FLAGS_BIT:
        if first_present & PRESENT_TSFT_BIT:
            offset = _aligned(offset, TSFT_BYTES) + TSFT_BYTES
        if offset >= length:
            raise RadiotapError("radiotap Flags field past the header")
        flags = data[offset]
    return RadiotapHeader(length, flags)


def _aligned(offset: int, alignment: int) -> int:
    return (offset + alignment - 1) // alignment * alignment
