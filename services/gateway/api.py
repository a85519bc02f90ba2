"""The FastAPI application: routes only, fed by a GatewayBackend that builds the responses.

Read-only routes are open unless the config closes them; commands always need a named bearer
token whose role allows them (401 without a known token, 403 with a role that may not).
"""

from __future__ import annotations

import asyncio
import logging
from pathlib import Path
from typing import Callable, Protocol

from fastapi import Depends, FastAPI, HTTPException, Response, WebSocket, status
from fastapi.security import HTTPAuthorizationCredentials, HTTPBearer
from fastapi.staticfiles import StaticFiles

from coopdrive.services.gateway.auth import Command, Principal, TokenBook
from coopdrive.services.gateway.commands import (
    CommandOutcome,
    CommandResponse,
    EstopCommand,
    ModeCommand,
    PlannerForceCommand,
    RecordingCommand,
)
from coopdrive.services.gateway.live import LiveBroadcaster
from coopdrive.services.gateway.metrics import CONTENT_TYPE
from coopdrive.services.gateway.models import HealthResponse, StateResponse
from coopdrive.services.gateway.view_models import PlannerResponse, SceneResponse, V2xStationsResponse

API_TITLE = "coopdrive gateway"
API_VERSION = "2"
STATIC_DIR = Path(__file__).parent / "static"
# WebSocket close code for a refused policy (RFC 6455): no valid token on a closed gateway.
WS_POLICY_VIOLATION = 1008
log = logging.getLogger(__name__)


class GatewayBackend(Protocol):
    live: LiveBroadcaster

    def health(self) -> HealthResponse: ...
    def state(self) -> StateResponse: ...
    def v2x_stations(self) -> V2xStationsResponse: ...
    def scene(self) -> SceneResponse: ...
    def planner(self) -> PlannerResponse: ...
    def metrics(self) -> bytes: ...
    def recent_commands(self) -> list[CommandResponse]: ...
    def refused(self, command: Command, who: str, detail: str) -> None: ...
    def mode(self, who: Principal, body: ModeCommand) -> CommandResponse: ...
    def estop(self, who: Principal, body: EstopCommand) -> CommandResponse: ...
    def planner_force(self, who: Principal, body: PlannerForceCommand) -> CommandResponse: ...
    def recording(self, who: Principal, body: RecordingCommand) -> CommandResponse: ...


def build_app(backend: GatewayBackend, tokens: TokenBook) -> FastAPI:
    app = FastAPI(title=API_TITLE, version=API_VERSION,
                  description="Health, live state and commands of one coopdrive vehicle, over its Zenoh bus.")
    bearer = HTTPBearer(auto_error=False, description="A token from the gateway's config (tokens, read_token).")
    _add_read_routes(app, backend, _read_guard(tokens, bearer))
    _add_command_routes(app, backend, _command_guard(backend, tokens, bearer))
    _add_live_route(app, backend, tokens)
    app.mount("/", StaticFiles(directory=STATIC_DIR, html=True), name="hmi")
    return app


def _read_guard(tokens: TokenBook, bearer: HTTPBearer) -> Callable[..., None]:
    """The dependency of the read-only routes: 401 unless the gateway is open or the token may read."""
    def may_read(credentials: HTTPAuthorizationCredentials | None = Depends(bearer)) -> None:
        if not tokens.may_read(credentials.credentials if credentials else None):
            raise HTTPException(status.HTTP_401_UNAUTHORIZED, "a valid bearer token is needed",
                                headers={"WWW-Authenticate": "Bearer"})
    return may_read


def _command_guard(backend: GatewayBackend, tokens: TokenBook,
                   bearer: HTTPBearer) -> Callable[[Command], Callable[..., Principal]]:
    """allowed(command): the dependency naming who sends it; 401 without a known token, 403 for a role that
    may not (both remembered by the backend as refused commands)."""
    def allowed(command: Command) -> Callable[..., Principal]:
        def who_may(credentials: HTTPAuthorizationCredentials | None = Depends(bearer)) -> Principal:
            who = tokens.identify(credentials.credentials if credentials else None)
            if who is None:
                backend.refused(command, "unknown", "no valid bearer token")
                raise HTTPException(status.HTTP_401_UNAUTHORIZED, f"{command.value} needs a valid bearer token",
                                    headers={"WWW-Authenticate": "Bearer"})
            if not who.may(command):
                backend.refused(command, who.name, f"role {who.role.value} may not")
                raise HTTPException(status.HTTP_403_FORBIDDEN,
                                    f"{who.name} ({who.role.value}) may not {command.value}")
            return who
        return who_may
    return allowed


def _add_read_routes(app: FastAPI, backend: GatewayBackend, may_read: Callable[..., None]) -> None:
    read = {"dependencies": [Depends(may_read)], "tags": ["read"]}

    @app.get("/health", response_model=HealthResponse, summary="Liveliness, message age and rate of every service",
             **read)
    def get_health() -> HealthResponse:
        return backend.health()

    @app.get("/state", response_model=StateResponse,
             summary="Latest ego state, scene, planner state, control command and actuation status", **read)
    def get_state() -> StateResponse:
        return backend.state()

    @app.get("/v2x/stations", response_model=V2xStationsResponse,
             summary="Remote ITS stations: link statistics and trust, from v2x/status", **read)
    def get_stations() -> V2xStationsResponse:
        return backend.v2x_stations()

    @app.get("/scene", response_model=SceneResponse, summary="Tracked objects with per-property confidence", **read)
    def get_scene() -> SceneResponse:
        return backend.scene()

    @app.get("/planner", response_model=PlannerResponse,
             summary="Planner state machine, its graph (Mermaid) and recent transitions", **read)
    def get_planner() -> PlannerResponse:
        return backend.planner()

    @app.get("/commands", response_model=list[CommandResponse], summary="The latest commands, who and why", **read)
    def get_commands() -> list[CommandResponse]:
        return backend.recent_commands()

    @app.get("/metrics", response_class=Response, summary="Prometheus text exposition", **read,
             responses={200: {"content": {CONTENT_TYPE: {}}}})
    def get_metrics() -> Response:
        return Response(content=backend.metrics(), media_type=CONTENT_TYPE)


def _answered(result: CommandResponse, response: Response) -> CommandResponse:
    """A command not carried out is answered 409 (its detail says why); one carried out, 202."""
    if result.outcome is CommandOutcome.REFUSED:
        response.status_code = status.HTTP_409_CONFLICT
    return result


def _add_command_routes(app: FastAPI, backend: GatewayBackend,
                        allowed: Callable[[Command], Callable[..., Principal]]) -> None:
    command = {"tags": ["command"], "response_model": CommandResponse, "status_code": status.HTTP_202_ACCEPTED,
               "responses": {409: {"model": CommandResponse, "description": "Not carried out; detail says why"}}}

    @app.post("/mode", summary="Request a driving mode (published as ModeRequest on gateway/mode_request)",
              **command)
    def post_mode(body: ModeCommand, response: Response,
                  who: Principal = Depends(allowed(Command.MODE))) -> CommandResponse:
        return _answered(backend.mode(who, body), response)

    @app.post("/estop", summary="Emergency stop (published as EmergencyStop on gateway/estop)", **command)
    def post_estop(body: EstopCommand, response: Response,
                   who: Principal = Depends(allowed(Command.ESTOP))) -> CommandResponse:
        return _answered(backend.estop(who, body), response)

    @app.post("/planner/force", summary="Put the planner's machine in a state by name", **command)
    def post_force(body: PlannerForceCommand, response: Response,
                   who: Principal = Depends(allowed(Command.PLANNER_FORCE))) -> CommandResponse:
        return _answered(backend.planner_force(who, body), response)

    @app.post("/recording", summary="Start or stop recording what the gateway hears to MCAP", **command)
    def post_recording(body: RecordingCommand, response: Response,
                       who: Principal = Depends(allowed(Command.RECORDING))) -> CommandResponse:
        return _answered(backend.recording(who, body), response)


def _add_live_route(app: FastAPI, backend: GatewayBackend, tokens: TokenBook) -> None:
    @app.websocket("/ws")
    async def live(websocket: WebSocket, token: str | None = None) -> None:
        """Live frames (LiveFrame JSON); a browser passes its token as ?token=, others may use the header."""
        header = websocket.headers.get("authorization", "")
        offered = token or (header[len("Bearer "):] if header.startswith("Bearer ") else None)
        if not tokens.may_read(offered):
            await websocket.close(code=WS_POLICY_VIOLATION)
            return
        await websocket.accept()
        sending = asyncio.create_task(backend.live.serve(websocket.send_text))
        sending.add_done_callback(lambda task: task.cancelled() or task.exception())  # retrieved: no warning
        try:
            # Listening too notices a close at once, not at the next send (a prompt shutdown, no stale clients).
            while (await websocket.receive())["type"] != "websocket.disconnect" and not sending.done():
                pass
        except Exception as error:  # noqa: BLE001 - any receive failure means the client is gone
            log.debug("live client left: %r", error)
        finally:
            sending.cancel()
