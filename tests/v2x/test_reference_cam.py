"""A CAM built bit by bit from the UPER layout of EN 302 637-2 v1.3.2, independently of our encoder."""

import math
import struct

import pytest

from coopdrive.v2x.packet import decode_packet
from coopdrive.v1 import its_pb2


class BitWriter:
    def __init__(self):
        self.bits = []

    def put(self, value, width):
        assert 0 <= value < 2**width, (value, width)
        self.bits += [(value >> (width - 1 - index)) & 1 for index in range(width)]

    def constrained(self, value, low, high):
        """UPER constrained whole number: value - low in the fewest bits holding high - low."""
        self.put(value - low, (high - low).bit_length())

    def to_bytes(self):
        bits = self.bits + [0] * (-len(self.bits) % 8)
        return bytes(int("".join(map(str, bits[i:i + 8])), 2) for i in range(0, len(bits), 8))


def reference_cam_uper() -> bytes:
    w = BitWriter()
    w.put(1, 8), w.put(2, 8), w.put(0x01020304, 32)        # ItsPduHeader: version 1, CAM, stationID
    w.put(40_000, 16)                                       # generationDeltaTime
    w.put(0, 1), w.put(0b10, 2)                             # CamParameters: no extension; LF present, special absent
    w.put(0, 1), w.constrained(5, 0, 255)                  # BasicContainer: no extension; passengerCar
    w.constrained(577_089_000, -900_000_000, 900_000_001)  # latitude 57.7089 deg
    w.constrained(119_735_000, -1_800_000_000, 1_800_000_001)  # longitude 11.9735 deg
    w.constrained(500, 0, 4095), w.constrained(300, 0, 4095)   # semi-major 5 m, semi-minor 3 m
    w.constrained(450, 0, 3601)                            # semi-major orientation 45 deg from north
    w.constrained(12_345, -100_000, 800_001)               # altitude 123.45 m
    w.put(6, 4)                                            # altitudeConfidence alt-001-00 (index 6 of 16)
    w.put(0, 1), w.put(0, 1)                               # HF CHOICE: no extension, basicVehicleContainerHF
    w.put(0b1000000, 7)                                    # optionals: only accelerationControl
    w.constrained(900, 0, 3601), w.constrained(10, 1, 127)  # heading east, within 1 deg
    w.constrained(2222, 0, 16383), w.constrained(50, 1, 127)  # 22.22 m/s within 0.5 m/s
    w.put(0, 2)                                            # driveDirection forward
    w.constrained(45, 1, 1023), w.put(0, 3)                # 4.5 m, noTrailerPresent
    w.constrained(18, 1, 62)                               # width 1.8 m
    w.constrained(-15, -160, 161), w.constrained(102, 0, 102)  # -1.5 m/s2, confidence unavailable
    w.constrained(300, -30_000, 30_001), w.put(7, 3)       # curvature 0.01 /m, confidence unavailable
    w.put(0, 1), w.put(0, 2)                               # curvatureCalculationMode yawRateUsed (extensible)
    w.constrained(-100, -32_766, 32_767), w.put(8, 4)      # yaw rate 1 deg/s right, confidence unavailable
    w.put(0b1000100, 7)                                    # accelerationControl: brake pedal, ACC engaged
    w.put(0, 1)                                            # LF CHOICE: no extension, one alternative
    w.put(0, 4)                                            # vehicleRole default
    w.put(0b10001000, 8)                                   # exteriorLights: low beam, daytime running
    w.constrained(1, 0, 40)                                # pathHistory with one point
    w.put(1, 1)                                            # pathDeltaTime present
    w.constrained(100, -131_071, 131_072), w.constrained(-200, -131_071, 131_072)
    w.constrained(12_800, -12_700, 12_800)                 # deltaAltitude unavailable
    w.put(0, 1), w.constrained(50, 1, 65_535)              # pathDeltaTime 0.5 s (extensible root value)
    return w.to_bytes()


def reference_gn_packet(uper: bytes) -> bytes:
    btp = struct.pack(">HH", 2001, 0)
    basic = bytes([0x01, 0x00, 0x05, 0x01])                # GN version 0, common header next, 1 s, 1 hop
    common = struct.pack(">BBBBHBB", 0x20, 0x50, 0x00, 0x80, len(btp) + len(uper), 1, 0)  # BTP-B, SHB, mobile
    position_vector = bytes.fromhex("1400" "020000000001") + struct.pack(">Iii", 1000, 577_089_000, 119_735_000) \
        + struct.pack(">HH", 0x8000 | 2222, 900)
    return basic + common + position_vector + bytes(4) + btp + uper


def test_a_hand_built_reference_cam_decodes_to_the_fields_it_was_built_from():
    decoded = decode_packet(reference_gn_packet(reference_cam_uper()))
    cam = decoded.content
    assert decoded.station_id == 0x01020304 and cam.generation_delta_time_ms == 40_000
    assert cam.station_type == its_pb2.STATION_TYPE_PASSENGER_CAR
    position = cam.reference_position
    assert position.latitude_deg == pytest.approx(57.7089) and position.longitude_deg == pytest.approx(11.9735)
    assert (position.semi_major_confidence_m, position.semi_minor_confidence_m) == pytest.approx((5.0, 3.0))
    assert position.semi_major_orientation_rad == pytest.approx(math.pi / 4)
    assert position.altitude_m == pytest.approx(123.45) and position.altitude_confidence_m == 1.0
    hf = cam.high_frequency
    assert hf.heading_rad == pytest.approx(0.0) and hf.heading_confidence_rad == pytest.approx(math.radians(1.0))
    assert hf.speed_mps == pytest.approx(22.22) and hf.speed_confidence_mps == pytest.approx(0.5)
    assert hf.drive_direction == its_pb2.DRIVE_DIRECTION_FORWARD
    assert hf.vehicle_length_m == pytest.approx(4.5) and hf.vehicle_width_m == pytest.approx(1.8)
    assert hf.longitudinal_acceleration_mps2 == pytest.approx(-1.5)
    assert not hf.HasField("longitudinal_acceleration_confidence_mps2")
    assert hf.curvature_per_m == pytest.approx(0.01) and not hf.HasField("curvature_confidence_per_m")
    assert hf.yaw_rate_radps == pytest.approx(-math.radians(1.0))
    assert hf.acceleration_control.brake_pedal_engaged and hf.acceleration_control.acc_engaged
    assert not hf.acceleration_control.gas_pedal_engaged and not hf.HasField("lane_position")
    lights = cam.low_frequency.exterior_lights
    assert lights.low_beam_headlights_on and lights.daytime_running_lights_on and not lights.fog_light_on
    (point,) = cam.low_frequency.path_history
    assert point.delta_latitude_deg == pytest.approx(1e-5) and point.delta_longitude_deg == pytest.approx(-2e-5)
    assert not point.HasField("delta_altitude_m") and point.delta_time_s == pytest.approx(0.5)
    assert decoded.gn.extended.source_position.speed_cmps == 2222


def test_our_encoder_produces_the_reference_bytes_from_the_decoded_content():
    from coopdrive.v2x.its_pdu import ItsCodec, ItsMessageId
    from coopdrive.v2x.mapping.cam import cam_to_asn
    uper = reference_cam_uper()
    decoded = decode_packet(reference_gn_packet(uper)).content
    assert ItsCodec().encode(ItsMessageId.CAM, cam_to_asn(decoded)) == uper
