"""The FastAPI application: routes only, fed by callables that build the responses."""

from __future__ import annotations

import secrets
from typing import Callable

from fastapi import Depends, FastAPI, HTTPException, status
from fastapi.security import HTTPAuthorizationCredentials, HTTPBearer

from coopdrive.services.gateway.models import HealthResponse, StateResponse

API_TITLE = "coopdrive gateway"
API_VERSION = "1"


def build_app(health: Callable[[], HealthResponse], state: Callable[[], StateResponse],
              read_token: str | None = None) -> FastAPI:
    """read_token None: read-only endpoints are open; otherwise they need `Authorization: Bearer <token>`."""
    app = FastAPI(title=API_TITLE, version=API_VERSION,
                  description="Health and live state of one coopdrive vehicle, read from its Zenoh bus.")
    bearer = HTTPBearer(auto_error=False, description="Needed only when the gateway's readonly_open is false.")

    def may_read(credentials: HTTPAuthorizationCredentials | None = Depends(bearer)) -> None:
        if read_token is None:
            return
        if credentials is None or not secrets.compare_digest(credentials.credentials.encode(), read_token.encode()):
            raise HTTPException(status.HTTP_401_UNAUTHORIZED, "a valid bearer token is needed",
                                headers={"WWW-Authenticate": "Bearer"})

    @app.get("/health", response_model=HealthResponse, dependencies=[Depends(may_read)], tags=["read"],
             summary="Liveliness, message age and rate of every service of the vehicle")
    def get_health() -> HealthResponse:
        return health()

    @app.get("/state", response_model=StateResponse, dependencies=[Depends(may_read)], tags=["read"],
             summary="Latest ego state, scene, planner state, control command and actuation status")
    def get_state() -> StateResponse:
        return state()

    return app
