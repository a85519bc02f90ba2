"""The traffic lights on messages our code did not write: a MAPEM and SPATEMs encoded by asn1tools compiled straight
from TS 103 301's modules (shared/asn1/dsrc) and decoded by our v2x path give the planner the decisions their
protobuf equivalent gives; the real roadside unit's signed SPATEM (shared/data/v2x) drives its advice."""

from __future__ import annotations

import json
import subprocess
import sys

import pytest
from planner_world import inputs
from signal_messages import asn_mapem, asn_spatem, decoded
from signal_world import AMBER, GREEN, PLANE, RED, ego_at, heard, light, mapem

from coopdrive.recording.capture import read_gn_packets
from coopdrive.services.planner.config import PlannerLogicConfig, SignalConfig
from coopdrive.services.planner.planner import Planner
from coopdrive.services.planner.signals.advice import Advice, Approach, advise
from coopdrive.services.planner.signals.spat_tracker import SpatTracker
from coopdrive.v2x.dsrc_time import unix_s_of_minute_of_year
from coopdrive.v2x.btp import BtpPort
from coopdrive.v2x.packet import decode_packet
from coopdrive.v2x.pcap import PcapWriter
from coopdrive.v2x.timebase import ItsClock
from coopdrive.v1 import planner_pb2
from tests.shared_data import shared_file
from tests.v2x import infrastructure_messages as messages

LIMIT_MPS = 13.9


def decision(map_content, spat_content, x_m: float, speed_mps: float = LIMIT_MPS, glosa: bool = True):
    p = Planner(PlannerLogicConfig(cruise_speed_mps=LIMIT_MPS), glosa=glosa)
    request, _ = p.step(0.0, inputs(planner_pb2.SCENARIO_FOLLOW, ego=ego_at(x_m, speed_mps),
                                    mapems=heard(map_content, 0.0), spatems=heard(spat_content, 0.0)))
    return (p.lights_machine.state.name, request.has_stop_line, round(request.stop_line_distance_m, 2),
            round(request.desired_speed_mps, 3))


SITUATIONS = [
    (-180.0, ((RED, 60.0), (GREEN, 90.0))),
    (-180.0, ((RED, 15.0), (GREEN, 45.0))),
    (-180.0, ((GREEN, 60.0),)),
    (-180.0, ((GREEN, 5.0), (AMBER, 8.0), (RED, 20.0), (GREEN, 50.0))),
    (-30.0, ((AMBER, 3.0), (RED, 30.0))),
    (-80.0, ((AMBER, 3.0), (RED, 30.0))),
]


@pytest.mark.parametrize("glosa", [True, False])
@pytest.mark.parametrize("x_m, phases", SITUATIONS)
def test_a_mapem_and_spatem_written_by_another_encoder_give_the_decisions_of_their_protobuf_equivalent(
        x_m, phases, glosa):
    theirs = decision(decoded("MAPEM", asn_mapem()), decoded("SPATEM", asn_spatem(phases)), x_m, glosa=glosa)
    ours = decision(mapem(), light(*phases), x_m, glosa=glosa)
    assert theirs == ours
    assert theirs[0] != "IDLE"


def real_spatem():
    packets = [packet.gn_packet for packet in read_gn_packets(shared_file("v2x/considerit_signed_testvectors.pcap"))]
    return decode_packet(packets[3]).content


def real_spat_time_unix_s(content) -> float:
    """The SPATEM's own time stamp (minute 470007 of the year, 4.456 s): 27 min 4.456 s after an hour began."""
    (intersection,) = content.intersections
    return unix_s_of_minute_of_year(2023, intersection.minute_of_year, intersection.second_of_minute_s)


@pytest.mark.parametrize("to_line_m, glosa, advice, speed_mps", [
    # Red until 1636.0 s of the hour, red-amber until 1638.0, green until 1666.0: 13.544 s from the stamp, +1 s.
    (150.0, True, Advice.GLOSA, 150.0 / 14.544),
    (150.0, False, Advice.STOP, LIMIT_MPS),
    # Green too far off for 20 km/h: stop.
    (30.0, True, Advice.STOP, LIMIT_MPS),
])
def test_the_real_rsus_spatem_drives_the_advice_for_its_first_signal_group(to_line_m, glosa, advice, speed_mps):
    content = real_spatem()
    now_s = real_spat_time_unix_s(content)
    tracker = SpatTracker(ItsClock(), SignalConfig().timing_tolerance_s)
    tracker.on_spatem(content, now_s)
    timing = tracker.latest[(30, 63, 1)]
    assert timing.current.end_s - now_s == pytest.approx(11.544)
    advised = advise(timing, Approach(now_s, to_line_m, LIMIT_MPS, LIMIT_MPS), SignalConfig(), glosa)
    assert (advised.advice, advised.speed_mps) == (advice, pytest.approx(speed_mps, rel=1e-3))


def test_the_real_rsus_spatem_reaches_the_planner_on_a_lane_of_its_intersection():
    content = real_spatem()
    now_s = real_spat_time_unix_s(content)
    p = Planner(PlannerLogicConfig(cruise_speed_mps=LIMIT_MPS))
    request, _ = p.step(now_s, inputs(planner_pb2.SCENARIO_FOLLOW, ego=ego_at(-163.8),
                                      mapems=heard(mapem(intersection_id=63, region=30), now_s),
                                      spatems=heard(content, now_s)))
    assert p.lights.view.status.name == "OK" and p.lights_machine.state.name == "GLOSA"
    assert request.desired_speed_mps == pytest.approx(150.0 / 14.544, rel=1e-3) and request.has_stop_line


def advise_command(capture, *options: str) -> list[str]:
    result = subprocess.run([sys.executable, "-m", "coopdrive.cli", "v2x", "advise", str(capture), *options],
                            capture_output=True, text=True, timeout=120, check=True)
    return result.stdout.splitlines()


def test_the_desk_tool_advises_on_the_real_rsus_spatem_for_a_signal_group_and_a_distance():
    (line,) = advise_command(shared_file("v2x/considerit_signed_testvectors.pcap"), "--intersection", "63",
                             "--group", "1", "--distance", "150", "--json")
    record = json.loads(line)
    assert (record["status"], record["light"], record["advice"]) == ("OK", "STOP", "GLOSA")
    assert (record["ends_in_s"], record["speed_mps"]) == (pytest.approx(11.544), pytest.approx(150.0 / 14.544))


# The start of a UTC hour: the capture's times are TimeMarks' seconds of the hour plus this.
HOUR_START_S = 1_700_002_800.0


def test_the_desk_tool_runs_the_planner_on_a_capture_of_another_encoders_mapem_and_spatems(tmp_path):
    capture = tmp_path / "rsu.pcap"
    with capture.open("wb") as stream:
        writer = PcapWriter(stream, messages.RSU_MAC)
        writer.write(messages.gn_packet(BtpPort.MAPEM, messages.encoded("MAPEM", asn_mapem())), HOUR_START_S)
        for t, phases in ((0.1, ((RED, 15.0), (GREEN, 45.0))), (15.2, ((GREEN, 45.0),))):
            uper = messages.encoded("SPATEM", asn_spatem(phases))
            writer.write(messages.gn_packet(BtpPort.SPATEM, uper), HOUR_START_S + t)
    latitude_deg, longitude_deg, _ = PLANE.to_geodetic(-180.0, -1.75)
    glosa, green = (json.loads(line) for line in advise_command(
        capture, "--lat", str(latitude_deg), "--lon", str(longitude_deg), "--heading", "90", "--json"))
    assert (glosa["state"], glosa["light"], green["state"]) == ("GLOSA", "STOP", "GO")
    assert glosa["speed_mps"] == pytest.approx(166.2 / 15.9, rel=1e-3)
