"""FlexStack (PyPI v2xflexstack 0.11.2, AGPL-3.0) as the live peer of our v2x service: an independent ETSI stack in
its own process, run by .venv-peers/bin/python (tools/peer_env.sh), never imported by coopdrive's package.

    .venv-peers/bin/python tests/v2x/live/flexstack_peer.py make-certs DIR
    .venv-peers/bin/python tests/v2x/live/flexstack_peer.py run --interface IF --station-id N --mac 02:..
        [--duration-s 10] [--denm] [--vam-station-id N] [--certs DIR [--trust OUR_PKI]] [--go-on-stdin]

`make-certs` writes a chain made by FlexStack's own certificate code (root.cert, aa.cert, at.cert and at.pem).
`run` puts a FlexStack station on the interface (raw link, ethertype 0x8947): GN router (MIB: GN version 1, its own
MAC), BTP, the CA basic service fed with a vehicle driving north, optionally a DENM, and with --certs its security
(sign and verify with that chain). It logs every CAM and DENM it decodes and prints ONE JSON summary at the end.

What /work/shared/notes/v2x-peers.md measured about this version is handled here; each place cites the note.
"""

import argparse
import collections
import json
import sys
import threading
import time
from pathlib import Path

from flexstack.btp.router import Router as BTPRouter
from flexstack.btp.service_access_point import BTPDataRequest, CommonNH, CommunicationProfile
from flexstack.facilities.ca_basic_service.ca_basic_service import CooperativeAwarenessBasicService
from flexstack.facilities.ca_basic_service.cam_transmission_management import VehicleData
from flexstack.facilities.vru_awareness_service.vam_transmission_management import DeviceDataProvider
from flexstack.facilities.vru_awareness_service.vru_awareness_service import VRUAwarenessService
from flexstack.facilities.decentralized_environmental_notification_service.den_service import (
    DecentralizedEnvironmentalNotificationService)
from flexstack.facilities.decentralized_environmental_notification_service.denm_transmission_management import (
    DecentralizedEnvironmentalNotificationMessage)
from flexstack.geonet.gn_address import GNAddress, M, MID, ST
from flexstack.geonet.mib import MIB, GnSecurity
from flexstack.geonet.router import Router as GNRouter
from flexstack.geonet.service_access_point import Area, GeoBroadcastHST, HeaderType, PacketTransportType
from flexstack.linklayer.raw_link_layer import RawLinkLayer
from flexstack.security.certificate import Certificate, OwnCertificate
from flexstack.security.certificate_library import CertificateLibrary
from flexstack.security.ecdsa_backend import PythonECDSABackend
from flexstack.security.security_profiles import SecurityProfile
from flexstack.security.sign_service import SignService
from flexstack.security.verify_service import VerifyService
from flexstack.utils.static_location_service import generate_tpv_dict_with_current_timestamp
from flexstack.utils.time_service import TimeService

from peer_certs import CHAIN_FILES, make_chain

CAM_PORT, DENM_PORT, VAM_PORT = 2001, 2002, 2018
MESSAGE_OF_PORT = {CAM_PORT: "cams", DENM_PORT: "denms", VAM_PORT: "vams"}
# ETSI StationType of the VRU whose VAMs the peer sends with --vam-station-id.
STATION_TYPE_PEDESTRIAN = 1
PSID_DENM = 37
PERIOD_S = 0.1
METRES_PER_DEGREE_LATITUDE = 111_320.0
# DENM: a stationary vehicle (cause 94, no sub cause) where the peer is, valid 60 s, sent twice a second.
DENM_EVENT = ("stationaryVehicle94", 0)
DENM_VALIDITY_S, DENM_INTERVAL_S = 60, 0.5
DENM_AREA_RADIUS_M = 500
# Units of the ETSI data elements as FlexStack's decoded dicts hold them.
SPEED_UNITS_PER_MPS = 100
POSITION_UNITS_PER_DEG = 10_000_000


class Log:
    """What this station decoded, refused and sent; filled by FlexStack's threads."""

    def __init__(self):
        self.lock = threading.Lock()
        self.cams: dict[int, dict] = {}
        self.denms: dict[int, dict] = {}
        self.sent = collections.Counter()
        self.verify_reports = collections.Counter()
        self.receive_errors = collections.Counter()
        self.our_chain: dict = {}

    def on_cam(self, cam: dict) -> None:
        station_id = cam["header"]["stationId"]
        basic = cam["cam"]["camParameters"]["basicContainer"]["referencePosition"]
        high = cam["cam"]["camParameters"]["highFrequencyContainer"][1]
        with self.lock:
            heard = self.cams.setdefault(station_id, {"count": 0})
            heard["count"] += 1
            heard["speed_mps"] = high["speed"]["speedValue"] / SPEED_UNITS_PER_MPS
            heard["latitude_deg"] = basic["latitude"] / POSITION_UNITS_PER_DEG
            heard["longitude_deg"] = basic["longitude"] / POSITION_UNITS_PER_DEG
            heard["protocol_version"] = cam["header"]["protocolVersion"]
        print(f"flexstack: CAM from station {station_id} at {heard['speed_mps']} m/s", file=sys.stderr)

    def on_denm(self, denm: dict) -> None:
        management = denm["denm"]["management"]
        with self.lock:
            heard = self.denms.setdefault(denm["header"]["stationId"], {"count": 0})
            heard["count"] += 1
            heard["originating_station_id"] = management["actionId"]["originatingStationId"]
            heard["termination"] = management.get("termination")
            heard["cause_code"] = denm["denm"].get("situation", {}).get("eventType", {}).get("ccAndScc", [None])[0]

    def summary(self) -> dict:
        with self.lock:
            return {"cams": {str(k): v for k, v in self.cams.items()},
                    "denms": {str(k): v for k, v in self.denms.items()}, "sent": dict(self.sent),
                    "verify_reports": dict(self.verify_reports), "receive_errors": dict(self.receive_errors),
                    "our_chain_kept": self.our_chain}


def guarded(log: Log, receive):
    """The note: FlexStack's receive thread catches only NotImplementedError; any other exception in its receive path
    ends its reception silently. So every packet is handed on inside a guard that counts what was raised (GN 0
    packets included, refused as 'Version not implemented')."""

    def on_packet(packet: bytes) -> None:
        try:
            receive(packet)
        except Exception as error:  # noqa: BLE001 - the peer must keep listening whatever a packet does
            with log.lock:
                log.receive_errors[f"{type(error).__name__}: {error}"] += 1

    return on_packet


def counted_by_port(log: Log, request_data):
    """FlexStack's BTP data request, counting what it is asked to send by message (its BTP destination port)."""

    def call(request: BTPDataRequest):
        with log.lock:
            log.sent[MESSAGE_OF_PORT.get(request.destination_port, str(request.destination_port))] += 1
        return request_data(request)

    return call


def trust_our_chain(library: CertificateLibrary, trust: Path) -> dict:
    """Our root and authority (`coopdrive pki init` DIR: root.cert, aa.cert) offered to FlexStack's library, which
    keeps a certificate only when it verifies its way (and drops the rest silently): what it kept, or why not."""
    kept = {}
    try:
        root = Certificate().decode((trust / "root.cert").read_bytes(), issuer=None)
        library.add_root_certificate(root)
        kept["root"] = root.as_hashedid8() in library.known_root_certificates
        authority = Certificate().decode((trust / "aa.cert").read_bytes(), issuer=root)
        library.add_authorization_authority(authority)
        kept["aa"] = authority.as_hashedid8() in library.known_authorization_authorities
    except Exception as error:  # noqa: BLE001 - what its decoder or verifier raises is the finding
        kept["error"] = f"{type(error).__name__}: {error}"
    return kept


def security_services(certs: Path, trust: Path | None, log: Log) -> tuple[SignService, VerifyService]:
    backend = PythonECDSABackend()
    files = {name: certs / file for name, file in CHAIN_FILES.items()}
    root = Certificate().decode(files["root"].read_bytes(), issuer=None)
    authority = Certificate().decode(files["aa"].read_bytes(), issuer=root)
    key_id = backend.import_signing_key(files["at_key"].read_bytes())
    ticket = Certificate().decode(files["at"].read_bytes(), issuer=authority)
    own = OwnCertificate(certificate=ticket.certificate, issuer=authority, key_id=key_id)
    library = CertificateLibrary(ecdsa_backend=backend, root_certificates=[root], aa_certificates=[authority],
                                 at_certificates=[own])
    library.add_own_certificate(own)
    if trust is not None:
        log.our_chain = trust_our_chain(library, trust)
    sign = SignService(backend=backend, certificate_library=library)
    verify = VerifyService(backend=backend, certificate_library=library, sign_service=sign)
    plain_verify = verify.verify

    def logged_verify(request):
        confirm = plain_verify(request)
        with log.lock:
            log.verify_reports[confirm.report.name] += 1
        return confirm

    verify.verify = logged_verify
    return sign, verify


def denm_request(station: VehicleData, tpv: dict, coder) -> BTPDataRequest:
    """One DENM of ours, built here rather than by FlexStack's DEN service, because of two findings of the note:
    its template leaves `termination: isCancellation` and `validityDuration: 0` set (its DENMs arrive as expired
    cancellations: so no termination and a validity > 0 here), and its DENM security profile cannot send an unsigned
    DENM without a SignService (so NO_SECURITY here)."""
    message = DecentralizedEnvironmentalNotificationMessage()
    message.fullfill_with_vehicle_data(station)
    management = message.denm["denm"]["management"]
    del management["termination"]
    now_its_ms = int(TimeService.timestamp_its())
    management.update(validityDuration=DENM_VALIDITY_S, detectionTime=now_its_ms, referenceTime=now_its_ms,
                      stationType=station.station_type)
    management["eventPosition"].update(latitude=int(tpv["lat"] * POSITION_UNITS_PER_DEG),
                                       longitude=int(tpv["lon"] * POSITION_UNITS_PER_DEG))
    message.denm["denm"]["situation"] = {"informationQuality": 1, "eventType": {"ccAndScc": DENM_EVENT}}
    data = coder.encode(message.denm)
    return BTPDataRequest(
        btp_type=CommonNH.BTP_B, destination_port=DENM_PORT,
        gn_packet_transport_type=PacketTransportType(header_subtype=GeoBroadcastHST.GEOBROADCAST_CIRCLE,
                                                     header_type=HeaderType.GEOBROADCAST),
        gn_area=Area(a=DENM_AREA_RADIUS_M, b=0, angle=0, latitude=management["eventPosition"]["latitude"],
                     longitude=management["eventPosition"]["longitude"]),
        communication_profile=CommunicationProfile.UNSPECIFIED, security_profile=SecurityProfile.NO_SECURITY,
        its_aid=PSID_DENM, data=data, length=len(data))


class Station:
    """FlexStack's layers wired on the interface, as its own examples wire them."""

    def __init__(self, args: argparse.Namespace, log: Log):
        self.log, self.args = log, args
        mac = bytes.fromhex(args.mac.replace(":", ""))
        sign, verify = security_services(args.certs, args.trust, log) if args.certs else (None, None)
        mib = MIB(itsGnLocalGnAddr=GNAddress(m=M.GN_MULTICAST, st=ST.PASSENGER_CAR, mid=MID(mac)),
                  itsGnSecurity=GnSecurity.ENABLED if args.certs else GnSecurity.DISABLED)
        self.gn = GNRouter(mib=mib, sign_service=sign, verify_service=verify)
        self.btp = BTPRouter(self.gn)
        self.gn.register_indication_callback(self.btp.btp_data_indication)
        self.vehicle = VehicleData(station_id=args.station_id, station_type=5, drive_direction="forward")
        self.ca = CooperativeAwarenessBasicService(btp_router=self.btp, vehicle_data=self.vehicle)
        self.ca.cam_reception_management.add_application_callback(log.on_cam)
        self.den = DecentralizedEnvironmentalNotificationService(btp_router=self.btp, vehicle_data=self.vehicle)
        self.btp.register_indication_callback_btp(port=DENM_PORT, callback=self._on_denm)
        self.btp.btp_data_request = counted_by_port(log, self.btp.btp_data_request)
        self.btp.freeze_callbacks()
        self.link = RawLinkLayer(args.interface, mac, guarded(log, self.gn.gn_data_indicate))
        self.gn.link_layer = self.link
        self.vru = self.vru_gn = None
        if args.vam_station_id is not None:
            # A pedestrian beside the vehicle, sending VAMs (TS 103 300-3) from a device of its own: its own GN
            # address (MAC), router and link on the same interface. (Behind the vehicle's router its VAMs would
            # come from the vehicle's GN address under another station id, which a receiver rightly refuses.)
            vru_mac = bytes.fromhex(args.vam_mac.replace(":", ""))
            self.vru_gn = GNRouter(mib=MIB(itsGnLocalGnAddr=GNAddress(m=M.GN_MULTICAST, st=ST.PEDESTRIAN,
                                                                      mid=MID(vru_mac))))
            vru_btp = BTPRouter(self.vru_gn)
            self.vru = VRUAwarenessService(btp_router=vru_btp, device_data_provider=DeviceDataProvider(
                station_id=args.vam_station_id, station_type=STATION_TYPE_PEDESTRIAN))
            vru_btp.btp_data_request = counted_by_port(log, vru_btp.btp_data_request)
            vru_btp.freeze_callbacks()
            self.vru_gn.link_layer = RawLinkLayer(args.interface, vru_mac, guarded(log, self.vru_gn.gn_data_indicate))

    def _on_denm(self, indication) -> None:
        """FlexStack's own DENM reception (its log, its LDM when it has one), then ours of what it decoded."""
        self.den.denm_reception_management.reception_callback(indication)
        self.log.on_denm(self.den.denm_coder.decode(indication.data))

    def drive(self) -> None:
        """A vehicle driving north at speed_mps for duration_s: its position fed to GN and the CA service every
        PERIOD_S (FlexStack sends about 10 Hz when moving, the note); a DENM every DENM_INTERVAL_S with --denm."""
        self.ca.start()
        start_s = next_denm_s = time.monotonic()
        while (elapsed_s := time.monotonic() - start_s) < self.args.duration_s:
            tpv = generate_tpv_dict_with_current_timestamp(
                self.args.latitude + self.args.speed_mps * elapsed_s / METRES_PER_DEGREE_LATITUDE, self.args.longitude)
            tpv.update(speed=self.args.speed_mps, track=0.0, altHAE=tpv["alt"], epd=1.0)
            self.gn.refresh_ego_position_vector(tpv)
            self.ca.cam_transmission_management.location_service_callback(tpv)
            if self.vru is not None:
                self.vru_gn.refresh_ego_position_vector(tpv)
                self.vru.vam_transmission_management.location_service_callback(tpv)
            if self.args.denm and time.monotonic() >= next_denm_s:
                next_denm_s += DENM_INTERVAL_S
                self.btp.btp_data_request(denm_request(self.vehicle, tpv, self.den.denm_coder))
            time.sleep(PERIOD_S)
        self.ca.stop()


def main() -> None:
    parser = argparse.ArgumentParser(description="FlexStack as a live V2X peer (tests/v2x/live)")
    commands = parser.add_subparsers(dest="command", required=True)
    make = commands.add_parser("make-certs", help="a certificate chain made by FlexStack's code")
    make.add_argument("directory", type=Path)
    run = commands.add_parser("run", help="a FlexStack station on a raw link; one JSON summary at the end")
    run.add_argument("--interface", required=True)
    run.add_argument("--station-id", type=int, required=True)
    run.add_argument("--mac", required=True)
    run.add_argument("--duration-s", type=float, default=10.0)
    run.add_argument("--speed-mps", type=float, default=10.0)
    run.add_argument("--latitude", type=float, default=51.4758)
    run.add_argument("--longitude", type=float, default=5.6247)
    run.add_argument("--denm", action="store_true")
    run.add_argument("--vam-station-id", type=int, help="also send VAMs of a pedestrian with this station id")
    run.add_argument("--vam-mac", default="02:00:00:00:42:50", help="the pedestrian's device's GN address (MAC)")
    run.add_argument("--certs", type=Path, help="sign and verify with the chain make-certs wrote here")
    run.add_argument("--trust", type=Path, help="with --certs: also trust our PKI (root.cert, aa.cert) here")
    run.add_argument("--go-on-stdin", action="store_true", help="print 'ready', start when a line arrives on stdin")
    args = parser.parse_args()
    if args.command == "make-certs":
        make_chain(args.directory)
        return
    log = Log()
    station = Station(args, log)
    if args.go_on_stdin:
        # As our_station.py: both stations start the exchange at once (the test says go when both are ready).
        print("ready", flush=True)
        sys.stdin.readline()
    station.drive()
    print(json.dumps(log.summary()), flush=True)


if __name__ == "__main__":
    main()
