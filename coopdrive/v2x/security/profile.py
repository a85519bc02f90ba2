"""What TS 103 097 v1.3.1 and the facilities expect of a secured CAM, DENM or iCLCM, and the security modes."""

from __future__ import annotations

import enum

from coopdrive.v2x.btp import BtpPort

SECURED_DATA_PROTOCOL_VERSION = 3
# ITS-AIDs (ISO TS 17419): CA basic service and DEN basic service.
PSID_CAM = 36
PSID_DENM = 37
# iCLCM (GCDC 2016) has no registered ITS-AID. It gets its own local value rather than the CA one so that
# a ticket allowed to send awareness messages is not thereby allowed to send platoon/merge commands.
# 127 is unused by the ETSI ITS-AIDs we know of; change it here (and in the tickets) if an assignment appears.
PSID_ICLCM = 127
# ETSI TS 102 965 ITS-AIDs of the other services whose messages real stations sign.
PSID_SPATEM, PSID_MAPEM, PSID_IVIM, PSID_SREM, PSID_SSEM, PSID_VAM, PSID_CPM = 137, 138, 139, 140, 637, 638, 639
PSID_OF_PORT = {int(BtpPort.CAM): PSID_CAM, int(BtpPort.DENM): PSID_DENM, int(BtpPort.ICLCM): PSID_ICLCM,
                int(BtpPort.SPATEM): PSID_SPATEM, int(BtpPort.MAPEM): PSID_MAPEM, int(BtpPort.IVIM): PSID_IVIM,
                int(BtpPort.SREM): PSID_SREM, int(BtpPort.SSEM): PSID_SSEM, int(BtpPort.VAM): PSID_VAM,
                int(BtpPort.CPM): PSID_CPM}
TICKET_PSIDS = (PSID_CAM, PSID_DENM, PSID_ICLCM)
# A roadside unit's ticket also permits the intersection's map and signal states; a vehicle's does not.
ROADSIDE_TICKET_PSIDS = TICKET_PSIDS + (PSID_SPATEM, PSID_MAPEM)

# Accept messages generated at most this long ago / ahead of our clock (GNSS-disciplined on both sides).
MAX_MESSAGE_AGE_S = 2.0
MAX_CLOCK_AHEAD_S = 0.5
# TS 103 097 v1.3.1 7.1.1: a CAM carries the full certificate once per second, a digest otherwise.
FULL_CERTIFICATE_INTERVAL_S = 1.0
# Elevation of generationLocation when the altitude is not known (ElevInt is 0.1 m, no "unknown" value).
ELEVATION_UNKNOWN = 0


class SecurityMode(enum.Enum):
    """How the v2x service treats the security envelope."""

    OFF = "off"                          # send unsigned; unwrap secured packets without verifying
    SIGN_ONLY = "sign_only"              # sign what we send; unwrap received ones without verifying
    SIGN_AND_VERIFY = "sign_and_verify"  # sign, verify and count failures, still deliver them (marked)
    VERIFY_REQUIRED = "verify_required"  # sign, verify, drop whatever fails, unsecured packets included

    @property
    def signs(self) -> bool:
        return self is not SecurityMode.OFF

    @property
    def verifies(self) -> bool:
        return self in (SecurityMode.SIGN_AND_VERIFY, SecurityMode.VERIFY_REQUIRED)

    @property
    def drops_failures(self) -> bool:
        return self is SecurityMode.VERIFY_REQUIRED
