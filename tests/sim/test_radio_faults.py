"""Radio faults the simulator carries out: a silent transmitter, and the first iCLCMs of a protocol step lost."""

import pytest

from coopdrive.services.sim.fault_config import IclcmDrop, IclcmFlag, PartnerSilent
from coopdrive.services.sim.radio_faults import RadioFaults
from coopdrive.v2x.packet import GnParams, SourcePosition, encode_cam, encode_iclcm
from coopdrive.v1 import its_pb2

STATION = 3011


def params():
    return GnParams(source_mac=bytes([2, 0, 0, 0, 11, 195]), station_type=5, gn_version=0, time_tai_ms=1000,
                    sequence_number=0, source_position=SourcePosition(51.47, 5.62, 10.0, 0.0))


def iclcm(**fields):
    return encode_iclcm(its_pb2.IclcmContent(station_id=STATION, **fields), params())


def test_a_silent_partner_sends_nothing_while_the_fault_lasts():
    faults = RadioFaults([PartnerSilent(type="partner_silent", vehicle_id="b1", start_s=10.0, end_s=12.0)])
    packet = iclcm()
    assert [faults.keeps("b1", packet, t) for t in (9.9, 10.0, 11.9, 12.0)] == [True, False, False, True]
    assert faults.keeps("b2", packet, 11.0)
    assert faults.silenced_count == 2


def test_only_the_first_iclcm_with_the_protocol_flag_set_is_lost():
    faults = RadioFaults([IclcmDrop(type="iclcm_drop", vehicle_id="b1", flag=IclcmFlag.MERGE_SAFE_TO_MERGE,
                                    start_s=0.0)])
    stom, plain = iclcm(merge_safe_to_merge=True), iclcm(forward_id=3003)
    assert faults.keeps("b1", plain, 1.0)
    assert not faults.keeps("b1", stom, 1.1)
    assert faults.keeps("b1", stom, 1.2)
    assert faults.dropped_count == 1


def test_the_first_iclcm_announcing_a_crossing_at_the_intersection_is_lost():
    faults = RadioFaults([IclcmDrop(type="iclcm_drop", vehicle_id="east1", flag=IclcmFlag.COUNTER_INTERSECTION,
                                    start_s=0.0)])
    before, crossed = iclcm(counter_intersection=0), iclcm(counter_intersection=1)
    assert faults.keeps("east1", before, 1.0)
    assert [faults.keeps("east1", crossed, t) for t in (2.0, 2.04)] == [False, True]


def test_an_id_field_counts_as_set_when_it_names_a_station_and_other_messages_pass():
    faults = RadioFaults([IclcmDrop(type="iclcm_drop", vehicle_id="b1", flag=IclcmFlag.FORWARD_ID, start_s=0.0,
                                    count=2)])
    cam = encode_cam(its_pb2.CamContent(station_id=STATION), params())
    assert faults.keeps("b1", cam, 1.0)
    assert [faults.keeps("b1", iclcm(forward_id=3003), t) for t in (1.0, 1.1, 1.2)] == [False, False, True]


def test_a_drop_fault_names_a_protocol_field():
    with pytest.raises(ValueError, match="flag"):
        IclcmDrop(type="iclcm_drop", vehicle_id="b1", flag="merge_please", start_s=0.0)


def test_with_a_duration_every_iclcm_with_the_flag_is_lost_for_that_long_from_the_first():
    faults = RadioFaults([IclcmDrop(type="iclcm_drop", vehicle_id="b1", flag=IclcmFlag.MERGE_REQUEST, start_s=0.0,
                                    duration_s=0.5)])
    request, plain = iclcm(merge_request=True), iclcm(forward_id=3003)
    assert faults.keeps("b1", plain, 1.0)
    assert [faults.keeps("b1", request, t) for t in (2.0, 2.04, 2.48, 2.5, 2.6)] == [False, False, False, True, True]
    assert faults.dropped_count == 3


def test_a_drop_fault_takes_a_count_or_a_duration_not_both():
    with pytest.raises(ValueError, match="not both"):
        IclcmDrop(type="iclcm_drop", vehicle_id="b1", flag="merge_request", start_s=0.0, count=2, duration_s=1.0)
