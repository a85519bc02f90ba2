"""The vehicle CAN adapter file: quantities as sums of signals in SI units, one config key for every service,
and one line naming the file and the problem when an adapter cannot be used."""

import math
import shutil

import pytest

from coopdrive.can.adapter import Quantity, VehicleCanAdapterError, load_adapter
from coopdrive.can.adapter_decoder import toyota_checksum
from coopdrive.runtime.config import ConfigError, load_config
from coopdrive.services.actuation.service import ActuationService
from coopdrive.services.geolocation.service import GeolocationService
from coopdrive.services.scene.service import SceneService
from tests.can.rav4_drive import RAV4_ADAPTER

RAV4_DBC = RAV4_ADAPTER.parent / "opendbc_toyota_new_mc_pt_generated.dbc"


def test_a_quantity_is_the_sum_of_its_signals_in_si_units_with_the_car_s_sign():
    steering = Quantity(message="STEER_ANGLE_SENSOR", signals=("STEER_ANGLE", "STEER_FRACTION"), unit="deg", sign=-1)
    assert steering.value({"STEER_ANGLE": -3.0, "STEER_FRACTION": -0.4}) == pytest.approx(math.radians(3.4))
    speed = Quantity(message="WHEEL_SPEEDS", signals=("WHEEL_SPEED_FL",), unit="km/h")
    assert speed.value({"WHEEL_SPEED_FL": 28.86}) == pytest.approx(8.016667, abs=1e-6)
    left = Quantity(message="BLINKERS_STATE", signals=("TURN_SIGNALS",), equals=(1,))
    assert [left.value({"TURN_SIGNALS": raw}) for raw in (1, 2, 3)] == [1.0, 0.0, 0.0]


def test_the_toyota_checksum_is_the_byte_sum_of_id_length_and_data():
    # The RAV4 log's first SPEED frame: (46408.584954) can0 0B4#000000001D0B7A5E
    data = bytes.fromhex("000000001D0B7A5E")
    assert toyota_checksum(0x0B4, data, 7) == 0x5E


@pytest.mark.parametrize("service", [GeolocationService, SceneService, ActuationService])
def test_every_service_takes_the_car_s_adapter_through_set_vehicle_can(service):
    config = load_config(service.Config, overrides=[f"vehicle_can={RAV4_ADAPTER}"])
    assert config.vehicle_can == str(RAV4_ADAPTER)


def write_adapter(tmp_path, text: str):
    shutil.copy(RAV4_DBC, tmp_path / RAV4_DBC.name)
    path = tmp_path / "car.yaml"
    path.write_text(RAV4_ADAPTER.read_text() + text)
    return path


@pytest.mark.parametrize("extra, named", [
    ("\nstate_requires: [NO_SUCH_MESSAGE]\n", "the DBC has no message NO_SUCH_MESSAGE"),
    ("\nstate_message: SPEED\nquantities: {wheel_speed_front_left: {message: SPEED, signals: [NOPE]}}\n",
     "wheel speeds are needed"),
    ("\ncheck_ranges: maybe\n", "check_ranges"),
])
def test_an_adapter_that_cannot_be_used_is_refused_in_one_line_naming_the_file_and_the_problem(tmp_path, extra, named):
    path = write_adapter(tmp_path, extra)
    with pytest.raises(VehicleCanAdapterError) as error:
        load_adapter(path)
    message = str(error.value)
    assert "\n" not in message and str(path) in message and named in message


def test_a_signal_the_dbc_does_not_have_is_named(tmp_path):
    path = write_adapter(tmp_path, "")
    path.write_text(path.read_text().replace("[YAW_RATE]", "[YAW_RATE_X]"))
    with pytest.raises(VehicleCanAdapterError, match="message KINEMATICS has no signal YAW_RATE_X"):
        load_adapter(path)


def test_a_missing_adapter_file_is_a_config_error_naming_it():
    with pytest.raises(ConfigError, match="vehicle_can: cannot read .*no-such-car.yaml"):
        load_config(GeolocationService.Config, overrides=["vehicle_can=no-such-car.yaml"])


def test_a_missing_dbc_beside_the_adapter_is_named(tmp_path):
    path = tmp_path / "car.yaml"
    path.write_text(RAV4_ADAPTER.read_text())
    with pytest.raises(VehicleCanAdapterError, match="cannot read DBC .*opendbc_toyota_new_mc_pt_generated.dbc"):
        load_adapter(path)
