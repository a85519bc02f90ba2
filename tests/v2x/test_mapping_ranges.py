"""The CAM and iCLCM mappings put every field of any content into its ASN.1 range, which lets the packet
codec skip asn1tools' own checks for those 25 Hz messages (ItsCodec.encode check_ranges=False) without
ever sending a truncated value. DENMs keep the checks; any content is sent or clearly refused."""

import pytest
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

from coopdrive.v2x.its_pdu import ItsCodec, ItsMessageId
from coopdrive.v2x.mapping.cam import cam_to_asn
from coopdrive.v2x.mapping.denm import denm_to_asn
from coopdrive.v2x.mapping.iclcm import iclcm_to_asn
from coopdrive.v2x.reasons import V2xEncodeError
from coopdrive.v1 import its_pb2
from tests.v2x.any_content import any_message

CODEC = ItsCodec()
UNCHECKED = {
    "CAM": (ItsMessageId.CAM, its_pb2.CamContent, cam_to_asn, (1, 2)),
    "iCLCM": (ItsMessageId.ICLCM, its_pb2.IclcmContent, iclcm_to_asn, (1,)),
}
HEALTH = [HealthCheck.too_slow, HealthCheck.data_too_large]


@pytest.mark.parametrize("kind", UNCHECKED)
@settings(max_examples=300, deadline=None, suppress_health_check=HEALTH)
@given(data=st.data())
def test_any_content_maps_to_values_that_pass_asn1tools_type_and_constraint_checks(kind, data):
    message_id, content_class, to_asn, versions = UNCHECKED[kind]
    content = data.draw(any_message(content_class))
    content.protocol_version = data.draw(st.sampled_from(versions))
    try:
        value = to_asn(content)
    except V2xEncodeError:  # a clear refusal (a code no clamp could make right) is allowed
        return
    checked = CODEC.encode(message_id, value, check_ranges=True)
    assert CODEC.encode(message_id, value, check_ranges=False) == checked


@settings(max_examples=300, deadline=None, suppress_health_check=HEALTH)
@given(content=any_message(its_pb2.DenmContent), protocol_version=st.sampled_from((1, 2)))
def test_any_denm_content_is_encoded_or_refused_with_an_encode_error(content, protocol_version):
    content.protocol_version = protocol_version
    try:
        uper = CODEC.encode(ItsMessageId.DENM, denm_to_asn(content))
    except V2xEncodeError:
        return
    assert CODEC.decode(uper)[0].station_id == content.station_id
