import marshal

import pytest

from coopdrive.v2x.its_pdu import ItsCodec, ItsMessageId, default_cache_dir, peek_its_header
from coopdrive.v2x.mapping.iclcm import iclcm_to_asn
from coopdrive.v2x.reasons import RejectReason, V2xDecodeError

from .messages import iclcm


def test_the_cache_lives_under_xdg_cache_home_when_it_is_set(monkeypatch, tmp_path):
    monkeypatch.setenv("XDG_CACHE_HOME", str(tmp_path))
    assert default_cache_dir() == tmp_path / "coopdrive" / "asn1"


def test_a_second_codec_loads_the_parsed_schema_from_the_disk_cache(tmp_path):
    ItsCodec(cache_dir=tmp_path).spec(1)
    (cached,) = tmp_path.iterdir()
    cached.write_bytes(marshal.dumps({"not": "a schema"}))  # damaged: must be rebuilt, not trusted
    codec = ItsCodec(cache_dir=tmp_path)
    uper = codec.encode(ItsMessageId.ICLCM, iclcm_to_asn(iclcm(True)))
    assert codec.decode(uper)[0].station_id == 2**32 - 1
    _, parsed = marshal.loads(cached.read_bytes())
    assert any("IgameCooperativeLaneChangeMessage" in module["types"] for module in parsed.values())


def test_the_its_header_is_read_from_the_first_six_bytes():
    header = peek_its_header(bytes([2, 10, 0, 0, 1, 0]) + b"rest")
    assert (header.protocol_version, header.message_id, header.station_id) == (2, 10, 256)
    with pytest.raises(V2xDecodeError, match="truncated_its_header"):
        peek_its_header(b"\x01\x02")


def test_an_iclcm_with_protocol_version_2_is_refused_because_only_gcdc_defined_it():
    uper = bytearray(ItsCodec().encode(ItsMessageId.ICLCM, iclcm_to_asn(iclcm(False))))
    uper[0] = 2
    with pytest.raises(V2xDecodeError) as error:
        ItsCodec().decode(bytes(uper))
    assert error.value.reason == RejectReason.UNSUPPORTED_PROTOCOL_VERSION


def test_garbage_after_a_valid_its_header_is_malformed_asn1():
    with pytest.raises(V2xDecodeError) as error:
        ItsCodec().decode(bytes([1, 2, 0, 0, 0, 1]))
    assert error.value.reason == RejectReason.MALFORMED_ASN1


def test_content_outside_the_asn1_ranges_is_an_encode_error_naming_the_message():
    from coopdrive.v2x.reasons import V2xEncodeError
    value = iclcm_to_asn(iclcm(False))
    value["iclm"]["generationDeltaTime"] = 70_000
    with pytest.raises(V2xEncodeError, match="ICLCM"):
        ItsCodec().encode(ItsMessageId.ICLCM, value)
    value["iclm"]["generationDeltaTime"] = 0
    value["header"]["protocolVersion"] = 3
    with pytest.raises(V2xEncodeError, match="unsupported_protocol_version"):
        ItsCodec().encode(ItsMessageId.ICLCM, value)
