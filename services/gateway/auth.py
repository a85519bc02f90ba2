"""TokenBook: who a bearer token belongs to and what that role may do (no network, no FastAPI)."""

from __future__ import annotations

import secrets
from dataclasses import dataclass
from enum import Enum

from coopdrive.services.gateway.config import GatewayConfig, Role

# The name requests with the legacy read_token are known by.
READ_TOKEN_NAME = "read_token"


class Command(str, Enum):
    MODE = "mode"
    ESTOP = "estop"
    PLANNER_FORCE = "planner_force"
    RECORDING = "recording"


ROLE_COMMANDS: dict[Role, frozenset[Command]] = {
    Role.OBSERVER: frozenset(),
    Role.OPERATOR: frozenset(Command),
}


@dataclass(frozen=True)
class Principal:
    name: str
    role: Role

    def may(self, command: Command) -> bool:
        return command in ROLE_COMMANDS[self.role]


class TokenBook:
    def __init__(self, tokens: dict[str, tuple[str, Role]], readonly_open: bool = True, read_token: str | None = None):
        self._tokens = {name: (secret.encode(), role) for name, (secret, role) in tokens.items()}
        if read_token is not None:
            self._tokens.setdefault(READ_TOKEN_NAME, (read_token.encode(), Role.OBSERVER))
        self.readonly_open = readonly_open

    @classmethod
    def from_config(cls, config: GatewayConfig) -> TokenBook:
        tokens = {name: (entry.token.get_secret_value(), entry.role) for name, entry in config.tokens.items()}
        read_token = config.read_token.get_secret_value() if config.read_token else None
        return cls(tokens, config.readonly_open, read_token)

    def identify(self, token: str | None) -> Principal | None:
        """The owner of token, None if nobody; every entry is compared so timing tells nothing."""
        if not token:
            return None
        offered = token.encode()
        found: Principal | None = None
        for name, (secret, role) in self._tokens.items():
            if secrets.compare_digest(offered, secret) and found is None:
                found = Principal(name, role)
        return found

    def may_read(self, token: str | None) -> bool:
        return self.readonly_open or self.identify(token) is not None
