"""Why a received packet was rejected: one enum, its values are the keys of V2xStatus.rejected_by_reason."""

import enum

from coopdrive.reasons import ReasonedError


class RejectReason(enum.Enum):
    TRUNCATED_BASIC_HEADER = "truncated_basic_header"
    UNSUPPORTED_GN_VERSION = "unsupported_gn_version"
    SECURED_PACKET_UNSUPPORTED = "secured_packet_unsupported"
    UNKNOWN_BASIC_NEXT_HEADER = "unknown_basic_next_header"
    TRUNCATED_COMMON_HEADER = "truncated_common_header"
    UNSUPPORTED_HEADER_TYPE = "unsupported_header_type"
    TRUNCATED_EXTENDED_HEADER = "truncated_extended_header"
    PAYLOAD_LENGTH_MISMATCH = "payload_length_mismatch"
    NOT_BTP_B = "not_btp_b"
    TRUNCATED_BTP_HEADER = "truncated_btp_header"
    UNKNOWN_BTP_PORT = "unknown_btp_port"
    TRUNCATED_ITS_HEADER = "truncated_its_header"
    MESSAGE_ID_PORT_MISMATCH = "message_id_port_mismatch"
    UNSUPPORTED_PROTOCOL_VERSION = "unsupported_protocol_version"
    MALFORMED_ASN1 = "malformed_asn1"
    UNMAPPABLE_CONTENT = "unmappable_content"
    # Security envelope (IEEE 1609.2 / TS 103 097 v1.3.1), see coopdrive/v2x/security/.
    MALFORMED_SECURITY_ENVELOPE = "malformed_security_envelope"
    UNSUPPORTED_SECURED_CONTENT = "unsupported_secured_content"
    UNSUPPORTED_HASH_ALGORITHM = "unsupported_hash_algorithm"
    UNSUPPORTED_SIGNER = "unsupported_signer"
    MISSING_GENERATION_TIME = "missing_generation_time"
    STALE_GENERATION_TIME = "stale_generation_time"
    FUTURE_GENERATION_TIME = "future_generation_time"
    UNKNOWN_SIGNER_DIGEST = "unknown_signer_digest"
    INVALID_CERTIFICATE = "invalid_certificate"
    UNKNOWN_ISSUER = "unknown_issuer"
    UNTRUSTED_ROOT = "untrusted_root"
    # What verify_required drops a valid signature for when its chain reaches no root we trust.
    UNTRUSTED = "untrusted"
    INVALID_CERTIFICATE_SIGNATURE = "invalid_certificate_signature"
    CERTIFICATE_NOT_YET_VALID = "certificate_not_yet_valid"
    CERTIFICATE_EXPIRED = "certificate_expired"
    OUTSIDE_CERTIFICATE_REGION = "outside_certificate_region"
    PSID_NOT_PERMITTED = "psid_not_permitted"
    PSID_PORT_MISMATCH = "psid_port_mismatch"
    INVALID_SIGNATURE = "invalid_signature"
    UNSECURED_PACKET_REFUSED = "unsecured_packet_refused"


class V2xDecodeError(ReasonedError[RejectReason]):
    """A packet that could not be decoded; `reason` says which layer refused it and why."""


class V2xEncodeError(ValueError):
    """Content that cannot be put on the wire (an identifier or code outside its ASN.1 range)."""
