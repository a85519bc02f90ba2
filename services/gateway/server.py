"""HttpServerThread: a uvicorn server on its own daemon thread, started and stopped from another.

The socket is bound in start(), so a taken port is reported there, not lost in the thread.
"""

from __future__ import annotations

import logging
import socket
import ssl
import threading

import uvicorn
from fastapi import FastAPI

from coopdrive.services.gateway.config import TlsConfig

log = logging.getLogger(__name__)

# Open connections get this long to finish their response when the server stops.
GRACEFUL_SHUTDOWN_S = 0.5
LISTEN_BACKLOG = 64


class HttpServerThread:
    def __init__(self, app: FastAPI, host: str, port: int, tls: TlsConfig | None = None):
        """tls: HTTPS; with tls.client_ca, mutual TLS (ssl_cert_reqs=CERT_REQUIRED): no client certificate, no API."""
        https = {}
        if tls is not None:
            https = {"ssl_certfile": str(tls.certfile), "ssl_keyfile": str(tls.keyfile)}
            if tls.client_ca is not None:
                https.update(ssl_ca_certs=str(tls.client_ca), ssl_cert_reqs=ssl.CERT_REQUIRED)
        # No per-message deflate on /ws: each client has its own compression context, so one live frame would
        # be compressed once per client, the gateway's largest cost with many clients, to save a few kB on a LAN.
        self._config = uvicorn.Config(app, host=host, port=port, log_config=None, access_log=False, lifespan="off",
                                      ws="websockets-sansio", ws_per_message_deflate=False,
                                      timeout_graceful_shutdown=GRACEFUL_SHUTDOWN_S, **https)
        self._server = uvicorn.Server(self._config)
        self._thread: threading.Thread | None = None
        self._socket: socket.socket | None = None
        self.error: BaseException | None = None

    def start(self) -> None:
        """Binds host:port (raises OSError if it cannot) and serves on a daemon thread."""
        family = socket.getaddrinfo(self._config.host, self._config.port, type=socket.SOCK_STREAM)[0][0]
        sock = socket.socket(family, socket.SOCK_STREAM)
        try:
            sock.setsockopt(socket.SOL_SOCKET, socket.SO_REUSEADDR, 1)
            sock.bind((self._config.host, self._config.port))
            sock.listen(LISTEN_BACKLOG)
        except OSError:
            sock.close()
            raise
        self._socket = sock
        self._thread = threading.Thread(target=self._serve, name="gateway-http", daemon=True)
        self._thread.start()

    def _serve(self) -> None:
        try:
            self._server.run(sockets=[self._socket])
        except BaseException as error:  # uvicorn exits with SystemExit on startup failure
            self.error = error
            log.error("gateway HTTP server stopped: %r", error)
        finally:
            self._socket.close()

    @property
    def running(self) -> bool:
        return self._thread is not None and self._thread.is_alive()

    @property
    def failed(self) -> bool:
        """The thread ended without being asked to."""
        return self._thread is not None and not self._thread.is_alive() and not self._server.should_exit

    def stop(self, timeout_s: float) -> bool:
        """Asks the server to exit and waits up to timeout_s; True if the thread has ended."""
        if self._thread is None:
            return True
        self._server.should_exit = True
        self._thread.join(timeout_s / 2)
        if self._thread.is_alive():
            self._server.force_exit = True  # stop waiting for slow clients
            self._thread.join(timeout_s / 2)
        return not self._thread.is_alive()
