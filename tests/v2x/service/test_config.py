from pathlib import Path

import pytest
from pydantic import ValidationError

from coopdrive.launch.stack_config import vehicle_overrides
from coopdrive.services.sim.intent_encoder import WORLD_V2X_PROFILE
from coopdrive.services.sim.scenario_config import load_scenario
from coopdrive.services.v2x.config import V2xConfig
from coopdrive.v2x.profile import V2xProfile
from coopdrive.v2x.generation import CamMode
from coopdrive.v1 import its_pb2

SCENARIOS = Path(__file__).resolve().parents[3] / "scenarios"


def test_the_defaults_are_today_s_etsi_stations_on_loopback_with_a_400_ms_loss_timeout():
    config = V2xConfig()
    assert (config.link.radio_host, config.link.listen_host) == ("127.0.0.1", "127.0.0.1")
    assert config.profile is V2xProfile.ETSI
    assert (config.gn_version, config.its_protocol_version, config.cam_mode) == (1, 2, CamMode.ETSI)
    assert config.loss_timeout_s == 0.4 and config.pcap_path is None
    assert config.clock_epoch_unix_s == 0.0


def test_the_gcdc_profile_is_one_setting_for_gn_0_cam_v1_at_25_hz_and_a_setting_of_its_own_still_wins():
    gcdc = V2xConfig(profile="gcdc")
    assert (gcdc.gn_version, gcdc.its_protocol_version, gcdc.cam_mode, gcdc.expected_rate_hz) == (
        0, 1, CamMode.GCDC, 25.0)
    assert V2xConfig(profile="gcdc", gn_version=1).gn_version == 1
    assert V2xConfig(profile="etsi", its_protocol_version=1).its_protocol_version == 1


def test_the_launcher_puts_its_stacks_on_the_profile_the_simulated_world_speaks():
    scenario = load_scenario(SCENARIOS / "follow.yaml")
    overrides = vehicle_overrides(scenario, scenario.vehicles[0].vehicle_id, radio=None)
    assert V2xConfig(**overrides["v2x"]).profile is WORLD_V2X_PROFILE is V2xProfile.GCDC


def test_the_station_type_is_given_by_name_or_code():
    assert V2xConfig(station_type="road_side_unit").station_type == its_pb2.STATION_TYPE_ROAD_SIDE_UNIT
    assert V2xConfig(station_type=8).station_type == its_pb2.STATION_TYPE_HEAVY_TRUCK


def test_the_mac_is_parsed_with_colons_or_dashes():
    assert V2xConfig(vehicle_mac="02-00-00-00-00-2A").mac_bytes == bytes.fromhex("02000000002a")


def test_the_clock_epoch_maps_sim_time_zero_to_a_utc_instant():
    assert V2xConfig(clock_epoch_utc="2016-05-28T10:00:00Z").clock_epoch_unix_s == 1_464_429_600.0


@pytest.mark.parametrize("key, value, complaint", [
    ("vehicle_mac", "02:00:00:00:01", "not 6 bytes"),
    ("vehicle_mac", "zz:00:00:00:00:01", "not hexadecimal"),
    ("station_type", "spaceship", "unknown station type"),
    ("gn_version", 2, "gn_version 2"),
    ("cam_mode", "sometimes", "cam_mode"),
    ("clock_epoch_utc", "2016-05-28T10:00:00", "time zone"),
    ("loss_timout_s", 0.4, "loss_timout_s"),
])
def test_a_bad_key_is_an_error_naming_it(key, value, complaint):
    with pytest.raises(ValidationError) as error:
        V2xConfig.model_validate({key: value})
    assert complaint in str(error.value)
