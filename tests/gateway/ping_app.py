"""The smallest app an HTTP server thread can serve, for the server's own tests (plain and TLS)."""

from fastapi import FastAPI


def ping_app() -> FastAPI:
    app = FastAPI()

    @app.get("/ping")
    def ping() -> dict:
        return {"pong": True}

    return app
