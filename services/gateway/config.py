"""Gateway configuration.

Example (YAML), operator and observer tokens, read-only endpoints closed, HTTPS with client certificates:

    host: 0.0.0.0
    readonly_open: false
    tokens:
      alice: {token: "<32+ random chars>", role: operator}
      dashboard: {token: "<32+ random chars>", role: observer}
    tls:
      certfile: /etc/coopdrive/gateway.crt
      keyfile: /etc/coopdrive/gateway.key
      client_ca: /etc/coopdrive/operators-ca.crt   # mTLS: uvicorn ssl_cert_reqs=CERT_REQUIRED
"""

from __future__ import annotations

from enum import Enum
from pathlib import Path

from pydantic import BaseModel, ConfigDict, Field, SecretStr, model_validator

from coopdrive.runtime.registry import VEHICLE_STACK
from coopdrive.runtime.service import ServiceConfig

DEFAULT_PORT = 8080
# Shorter tokens are guessable; refused at config time rather than discovered in the field.
MIN_TOKEN_CHARS = 8


class Role(str, Enum):
    OBSERVER = "observer"  # read-only endpoints, even when they are closed
    OPERATOR = "operator"  # also commands: mode, emergency stop, planner force, recording


class ApiToken(BaseModel):
    model_config = ConfigDict(extra="forbid")
    token: SecretStr = Field(min_length=MIN_TOKEN_CHARS)
    role: Role


class TlsConfig(BaseModel):
    """HTTPS for the API; with client_ca, mutual TLS: clients without a certificate from that CA are refused."""

    model_config = ConfigDict(extra="forbid")
    certfile: Path
    keyfile: Path
    client_ca: Path | None = None


class GatewayConfig(ServiceConfig):
    port: int = Field(DEFAULT_PORT, ge=1, le=65535)
    # Loopback by default: exposing the API beyond the vehicle is a deliberate choice.
    host: str = "127.0.0.1"
    # The vehicle whose services are watched; None: the vehicle the gateway runs for.
    vehicle_id: str | None = None
    # Read-only endpoints (/health, /state, /v2x/stations, /scene, /planner, /metrics, /ws) need no
    # credentials unless this is turned off; then read_token or any token of `tokens` is needed.
    readonly_open: bool = True
    # Bearer token for read-only endpoints when they are not open.
    read_token: SecretStr | None = None
    # Named bearer tokens and their roles; the name is who a command is logged as. Empty: no commands.
    tokens: dict[str, ApiToken] = Field(default_factory=dict)
    tls: TlsConfig | None = None
    # Services whose absence makes the overall status degraded.
    required_services: list[str] = Field(default_factory=lambda: ["sim", *VEHICLE_STACK])
    # A live service that has sent nothing for this long (vehicle clock) is reported silent.
    silent_after_s: float = Field(2.0, gt=0)
    # Wall-time window over which message rates are averaged.
    rate_window_s: float = Field(5.0, gt=0)
    # How long stop() waits for the HTTP server thread before abandoning it (it is a daemon).
    shutdown_timeout_s: float = Field(1.5, gt=0)
    # The HMI's clients must never delay a control cycle: on a shared machine the gateway takes CPU last.
    cpu_nice: int = Field(10, ge=0, le=19)
    # Frames per second of the live state on /ws.
    live_rate_hz: float = Field(15.0, ge=1.0, le=25.0)
    # Frames waiting per WebSocket client; beyond this the oldest is dropped (a slow client loses frames).
    live_queue_frames: int = Field(4, ge=1, le=100)
    # Where POST /recording writes MCAP files; None: recording is not offered.
    recording_dir: Path | None = None

    @model_validator(mode="after")
    def _closed_endpoints_need_a_token(self) -> GatewayConfig:
        if not self.readonly_open and self.read_token is None and not self.tokens:
            raise ValueError("readonly_open is false but no read_token or tokens are configured")
        secrets = [t.token.get_secret_value() for t in self.tokens.values()]
        if len(set(secrets)) != len(secrets):
            raise ValueError("two names in tokens share one token: commands could not be told apart")
        return self
