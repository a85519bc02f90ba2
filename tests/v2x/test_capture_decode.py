"""`coopdrive v2x decode` on the real captures of shared/data/v2x, as a user runs it, checked against tshark."""

import json
import random
import subprocess
import sys
from collections import Counter

import dpkt
import pytest

from coopdrive.v2x.btp import MESSAGE_NAME_OF_PORT
from coopdrive.recording.capture import read_capture
from coopdrive.services.v2x.capture_decode import CaptureDecoder
from coopdrive.v2x.pcap import PcapWriter
from tests.shared_data import shared_file
from tests.v2x.capture_wrap import wrap_capture, wrapped
from tests.v2x.test_tshark import tshark

SIGNED = "v2x/considerit_signed_testvectors.pcap"
FLEXSTACK = "v2x/flexstack_cam_vam_beacons.pcap"
MSVAN3T = "v2x/msvan3t_cam_cpm_trace.pcapng"
CAR_STATION, RSU_STATION, SPATEM_STATION = 3141730734, 12816437, 10430022
MUTANTS = 600
TSHARK_HEADER_TYPES = {"0x10": "beacon", "0x50": "tsb_single_hop", "0x40": "geobroadcast"}


def decode_json(*arguments: str) -> tuple[list[dict], dict]:
    result = subprocess.run([sys.executable, "-m", "coopdrive.cli", "v2x", "decode", *arguments, "--json"],
                            capture_output=True, text=True, timeout=120, check=True)
    lines = [json.loads(line) for line in result.stdout.splitlines()]
    return lines[:-1], lines[-1]["summary"]


def test_the_signed_capture_decodes_with_every_signature_verified_and_nothing_trusted_without_a_root():
    records, summary = decode_json(str(shared_file(SIGNED)))
    beacon, car, rsu, spatem = records
    assert (beacon["message_type"], beacon["gn"]["header_type"], beacon["security"]["signed"]) == \
        ("beacon", "beacon", False)
    assert car["message_type"] == "cam" and car["station_id"] == CAR_STATION
    assert car["content"]["high_frequency"]["speed_mps"] == pytest.approx(9.71)
    assert car["content"]["reference_position"]["latitude_deg"] == pytest.approx(47.8088, abs=1e-4)
    assert (car["security"]["verified"], car["security"]["trusted"], car["security"]["signer"]) == \
        (True, None, "certificate")
    assert (rsu["station_id"], rsu["security"]["verified"]) == (RSU_STATION, True)
    assert (spatem["message_type"], spatem["station_id"], spatem["security"]["verified"]) == \
        ("spatem", SPATEM_STATION, True)
    assert summary["signatures"] == {"unsigned": 1, "verified": 3} and summary["errors"] == {}


def test_freshness_is_judged_against_the_capture_time_and_can_be_skipped():
    # The capture's timestamps were made up (2023-11-14), days before the packets were signed.
    judged = [record["security"] for record in CaptureDecoder().records(shared_file(SIGNED))][1:]
    assert {(s["fresh"], s["reason"]) for s in judged} == {(False, "future_generation_time")}
    skipped = [record["security"] for record in CaptureDecoder(freshness=False).records(shared_file(SIGNED))][1:]
    assert {(s["fresh"], s["reason"], s["verified"]) for s in skipped} == {(None, None, True)}


def test_one_flipped_byte_in_the_cars_signature_fails_verification_and_the_content_is_still_shown(tmp_path):
    frames = list(read_capture(shared_file(SIGNED)))
    forged = bytearray(frames[1].gn_packet)
    forged[-1] ^= 0x01  # last byte of sSig
    path = tmp_path / "forged.pcap"
    with open(path, "wb") as stream:
        PcapWriter(stream, frames[1].source_mac).write(bytes(forged), frames[1].time_s)
    (record,) = CaptureDecoder().records(path)
    assert (record["security"]["verified"], record["security"]["reason"]) == (False, "invalid_signature")
    assert record["content"]["high_frequency"]["speed_mps"] == pytest.approx(9.71)


@pytest.mark.parametrize("name", [SIGNED, FLEXSTACK])
def test_the_same_capture_wrapped_as_radiotap_802_11_llc_decodes_identically(tmp_path, name):
    original = list(CaptureDecoder().records(shared_file(name)))
    wrapped = list(CaptureDecoder().records(wrap_capture(shared_file(name), tmp_path / "radiotap.pcap", "radiotap")))

    def comparable(record):
        return {key: value for key, value in record.items() if key not in ("link_type", "time_s")}
    assert [record["link_type"] for record in wrapped] == ["radiotap"] * len(original)
    assert [comparable(record) for record in wrapped] == [comparable(record) for record in original]


def tshark_counts(path) -> tuple[Counter, Counter, Counter]:
    """GN packets by header type, messages by type, (type, station) where tshark names the station."""
    result = subprocess.run([tshark(), "-r", str(path), "-T", "fields", "-e", "geonw.ch.htype", "-e", "btpb.dstport",
                             "-e", "its.stationID"], capture_output=True, text=True, timeout=120, check=True)
    header_types, messages, stations = Counter(), Counter(), Counter()
    for line in result.stdout.splitlines():
        header_type, port, station = line.split("\t")
        header_types[TSHARK_HEADER_TYPES[header_type]] += 1
        message = "beacon" if header_type == "0x10" else MESSAGE_NAME_OF_PORT[int(port)]
        messages[message] += 1
        if station:
            stations[(message, station)] += 1
    return header_types, messages, stations


@pytest.mark.parametrize("name", [MSVAN3T, FLEXSTACK, SIGNED])
def test_the_summary_counts_match_tsharks_on_the_same_capture(name):
    decoder = CaptureDecoder()
    records = list(decoder.records(shared_file(name)))
    summary = decoder.summary.as_dict()
    header_types, messages, stations = tshark_counts(shared_file(name))
    assert summary["gn_packets_by_header_type"] == dict(header_types)
    assert summary["messages_by_type"] == dict(messages)
    for (message, station), count in stations.items():
        assert summary["messages_by_type_and_station"][message][station] == count
    assert summary["errors"] == {} and summary["unreadable_frames"] == {}
    assert all("content" in record for record in records if record["message_type"] in ("cam", "cpm", "vam"))


def test_every_cam_of_the_ms_van3t_and_flexstack_captures_decodes_and_cpms_and_vams_are_decoded_too():
    for name, expected in ((MSVAN3T, {"cam": 367, "cpm": 562}), (FLEXSTACK, {"beacon": 9, "cam": 13, "vam": 13})):
        decoder = CaptureDecoder()
        records = list(decoder.records(shared_file(name)))
        assert decoder.summary.as_dict()["messages_by_type"] == expected
        cpm_or_vam = [r for r in records if r["message_type"] in ("cpm", "vam")]
        assert all(r["content"]["header"]["stationId"] == r["station_id"] for r in cpm_or_vam)


def test_mutated_frames_of_every_real_capture_decode_to_a_record_or_a_named_error_never_a_crash(tmp_path):
    rng = random.Random(2016)
    frames = [frame for name in (SIGNED, FLEXSTACK, MSVAN3T) for frame in read_capture(shared_file(name))]
    path = tmp_path / "mutants.pcap"
    with open(path, "wb") as stream:
        writer = dpkt.pcap.Writer(stream, snaplen=65535, linktype=127)
        for _ in range(MUTANTS):
            frame = rng.choice(frames)
            data = bytearray(wrapped("radiotap", frame.source_mac, frame.gn_packet))
            for _ in range(rng.randint(1, 4)):
                data[rng.randrange(len(data))] = rng.randrange(256)
            writer.writepkt(bytes(data[:rng.randint(1, len(data))] if rng.random() < 0.2 else data), 1.0)
    decoder = CaptureDecoder()
    records = list(decoder.records(path))
    assert len(records) == MUTANTS
    for record in records:
        assert "unreadable" in record or "gn" in record or "error" in record
    assert sum(decoder.summary.frames_by_link_type.values()) == MUTANTS
