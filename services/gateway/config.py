"""Gateway configuration."""

from __future__ import annotations

from pydantic import Field, SecretStr, model_validator

from coopdrive.runtime.registry import VEHICLE_STACK
from coopdrive.runtime.service import ServiceConfig

DEFAULT_PORT = 8080


class GatewayConfig(ServiceConfig):
    port: int = Field(DEFAULT_PORT, ge=1, le=65535)
    # Loopback by default: exposing the API beyond the vehicle is a deliberate choice.
    host: str = "127.0.0.1"
    # The vehicle whose services are watched; None: the vehicle the gateway runs for.
    vehicle_id: str | None = None
    # Read-only endpoints (/health, /state) need no credentials unless this is turned off.
    readonly_open: bool = True
    # Bearer token for read-only endpoints when they are not open.
    read_token: SecretStr | None = None
    # Services whose absence makes the overall status degraded.
    required_services: list[str] = Field(default_factory=lambda: ["sim", *VEHICLE_STACK])
    # A live service that has sent nothing for this long (vehicle clock) is reported silent.
    silent_after_s: float = Field(2.0, gt=0)
    # Wall-time window over which message rates are averaged.
    rate_window_s: float = Field(5.0, gt=0)
    # How long stop() waits for the HTTP server thread before abandoning it (it is a daemon).
    shutdown_timeout_s: float = Field(1.5, gt=0)

    @model_validator(mode="after")
    def _closed_endpoints_need_a_token(self) -> GatewayConfig:
        if not self.readonly_open and self.read_token is None:
            raise ValueError("readonly_open is false but no read_token is configured")
        return self
