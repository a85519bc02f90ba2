"""IntentEncoder: what scripted participants and roadside units broadcast, as real GeoNetworking packets.

Participants say what they would send (participants.MessageIntent, SI values in the local frame); this turns
each into the bytes a radio would carry, through the stack's own V2X code: CAMs from the v2x service's CAM
generator fed with the participant's state, DENMs and iCLCMs filled like the v2x service fills them, all
a signalised intersection's MAPEMs and SPATEMs as TS 103 301 has them (BTP ports 2003 and 2004), all wrapped by
V2xPacketCodec (BTP-B, single-hop or geo-broadcast).
"""

from __future__ import annotations

import datetime as dt
from typing import Callable

from coopdrive.geodesy import GeodeticOrigin
from coopdrive.services.sim.participants import IntentKind, MessageIntent
from coopdrive.v2x.generation import VehicleDimensions
from coopdrive.v2x.generation import CamGenerator
from coopdrive.messages.vehicle_frame import rear_overhang_m
from coopdrive.v2x.profile import PROFILE_DEFAULTS, V2xProfile
from coopdrive.v2x.packet import DestinationArea, GnParams, SourcePosition, V2xPacketCodec
from coopdrive.v2x.timebase import ItsClock, generation_delta_time_ms
from coopdrive.v1 import ego_pb2, its_pb2

ToGeodetic = Callable[[float, float], tuple[float, float, float]]
# The DENM reaches every vehicle within this distance of the event (geo-broadcast circle).
DENM_AREA_RADIUS_M = 1000.0
DENM_VALIDITY_S = 10.0
# The simulated world's stations speak GCDC 2016 (coopdrive/v2x/profile.py), and so do the stacks the launcher puts
# among them (launch/stack_config.py). The iCLCM is protocolVersion 1 in every profile.
WORLD_V2X_PROFILE = V2xProfile.GCDC
WORLD_PROFILE = PROFILE_DEFAULTS[WORLD_V2X_PROFILE]
ICLCM_PROTOCOL_VERSION = 1


# Field keys each intent kind may carry; anything else is refused so a new participant field is never dropped.
KNOWN_FIELDS = {
    IntentKind.CAM: {"x_m", "y_m", "heading_rad", "speed_mps", "accel_mps2", "yaw_rate_radps", "length_m",
                     "width_m", "lane", "emergency", "light_bar", "siren"},
    IntentKind.DENM: {"cause_code", "x_m", "y_m", "heading_rad", "speed_mps", "lane", "closed_lane", "length_m", "validity_s",
                      "since_s"},
    IntentKind.ICLCM: {"start_platoon", "end_of_scenario"},
    # A roadside unit's position, and the message's content as the v2x service decodes it (signal_rsu.py).
    IntentKind.MAPEM: {"x_m", "y_m", "content"},
    IntentKind.SPATEM: {"x_m", "y_m", "content"},
}


def station_mac(station_id: int) -> bytes:
    return bytes([0x02, 0x00]) + station_id.to_bytes(4, "big")


class IntentEncoder:
    def __init__(self, to_geodetic: ToGeodetic, utc_epoch: dt.datetime, gn_version: int = WORLD_PROFILE.gn_version):
        self._to_geodetic = to_geodetic
        self._clock = ItsClock(utc_epoch.timestamp())
        self._codec = V2xPacketCodec()
        self._gn_version = gn_version
        self._cams: dict[int, CamGenerator] = {}
        self._sequence: dict[int, int] = {}
        self._encoders = {IntentKind.CAM: self._cam, IntentKind.DENM: self._denm, IntentKind.ICLCM: self._iclcm,
                          IntentKind.MAPEM: self._mapem, IntentKind.SPATEM: self._spatem}

    def encode(self, intent: MessageIntent) -> bytes | None:
        """The packet for this intent; None when there is nothing to send yet (a CAM inside its period)."""
        unknown = sorted(set(intent.fields) - KNOWN_FIELDS[intent.kind])
        if unknown:
            raise ValueError(f"{intent.kind.name} intent from {intent.sender_id} has unmapped fields: {unknown}")
        return self._encoders[intent.kind](intent, self._clock.tai_ms(intent.time_s))

    # ----- per message ------------------------------------------------------------------------
    def _cam(self, intent: MessageIntent, tai_ms: int) -> bytes | None:
        fields = intent.fields
        station_type = its_pb2.STATION_TYPE_SPECIAL_VEHICLES if fields.get("emergency") else \
            its_pb2.STATION_TYPE_PASSENGER_CAR
        generator = self._cams.get(intent.station_id)
        if generator is None:
            generator = CamGenerator(WORLD_PROFILE.cam_mode, intent.station_id, station_type,
                                     WORLD_PROFILE.its_protocol_version,
                                     GeodeticOrigin(), VehicleDimensions(
                                         length_m=fields["length_m"], width_m=fields["width_m"],
                                         rear_axle_location_m=fields["length_m"] - rear_overhang_m(fields["length_m"])))
            self._cams[intent.station_id] = generator
        latitude_deg, longitude_deg, _ = self._to_geodetic(fields["x_m"], fields["y_m"])
        generator.on_ego_state(ego_pb2.EgoState(
            x_m=fields["x_m"], y_m=fields["y_m"], heading_rad=fields["heading_rad"], speed_mps=fields["speed_mps"],
            accel_mps2=fields["accel_mps2"], yaw_rate_radps=fields["yaw_rate_radps"], latitude_deg=latitude_deg,
            longitude_deg=longitude_deg, mode=ego_pb2.LOCALISATION_MODE_GNSS_PRECISE))
        content = generator.generate(intent.time_s, tai_ms)
        if content is None:
            return None
        return self._codec.encode_cam(content, self._params(intent, tai_ms, station_type))

    def _denm(self, intent: MessageIntent, tai_ms: int) -> bytes:
        fields = intent.fields
        latitude_deg, longitude_deg, _ = self._to_geodetic(fields["x_m"], fields["y_m"])
        # Road works come from a roadside unit (it names the closed lane); an emergency vehicle warns of itself.
        station_type = its_pb2.STATION_TYPE_ROAD_SIDE_UNIT if "closed_lane" in fields else \
            its_pb2.STATION_TYPE_SPECIAL_VEHICLES
        event = its_pb2.DenmContent(protocol_version=WORLD_PROFILE.its_protocol_version, station_id=intent.station_id,
                                    originating_station_id=intent.station_id, sequence_number=1,
                                    detection_time_tai_ms=self._clock.tai_ms(fields.get("since_s", intent.time_s)),
                                    reference_time_tai_ms=tai_ms,
                                    validity_duration_s=fields.get("validity_s", DENM_VALIDITY_S),
                                    station_type=station_type,
                                    relevance_distance=its_pb2.RELEVANCE_DISTANCE_LESS_THAN_1000M)
        event.event_position.latitude_deg, event.event_position.longitude_deg = latitude_deg, longitude_deg
        event.situation.event_type.cause_code = fields["cause_code"]
        if "closed_lane" in fields:
            event.alacarte.lane_position = fields["closed_lane"]
        params = self._params(intent, tai_ms, station_type)
        params.destination_area = DestinationArea(latitude_deg, longitude_deg, DENM_AREA_RADIUS_M)
        params.max_hop_limit = 10
        return self._codec.encode_denm(event, params)

    def _iclcm(self, intent: MessageIntent, tai_ms: int) -> bytes:
        fields = intent.fields
        content = its_pb2.IclcmContent(protocol_version=ICLCM_PROTOCOL_VERSION, station_id=intent.station_id,
                                       generation_delta_time_ms=generation_delta_time_ms(tai_ms),
                                       has_low_frequency=True, end_of_scenario=bool(fields.get("end_of_scenario")))
        if "start_platoon" in fields:
            content.start_platoon = fields["start_platoon"]
        return self._codec.encode_iclcm(content, self._params(intent, tai_ms, its_pb2.STATION_TYPE_ROAD_SIDE_UNIT))

    def _mapem(self, intent: MessageIntent, tai_ms: int) -> bytes:
        params = self._params(intent, tai_ms, its_pb2.STATION_TYPE_ROAD_SIDE_UNIT)
        return self._codec.encode_mapem(intent.fields["content"], params)

    def _spatem(self, intent: MessageIntent, tai_ms: int) -> bytes:
        params = self._params(intent, tai_ms, its_pb2.STATION_TYPE_ROAD_SIDE_UNIT)
        return self._codec.encode_spatem(intent.fields["content"], params)

    def _params(self, intent: MessageIntent, tai_ms: int, station_type: int) -> GnParams:
        fields = intent.fields
        latitude_deg, longitude_deg, _ = self._to_geodetic(fields.get("x_m", 0.0), fields.get("y_m", 0.0))
        sequence = self._sequence.get(intent.station_id, 0)
        self._sequence[intent.station_id] = (sequence + 1) % 65536
        return GnParams(source_mac=station_mac(intent.station_id), station_type=station_type,
                        gn_version=self._gn_version, time_tai_ms=tai_ms, sequence_number=sequence,
                        source_position=SourcePosition(latitude_deg, longitude_deg, fields.get("speed_mps", 0.0),
                                                       fields.get("heading_rad")))
