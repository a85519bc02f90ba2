"""What every link to the air shares: a socket read on a daemon thread until the link is closed."""

from __future__ import annotations

import socket
import threading

RECEIVE_POLL_S = 0.1


class LinkReader:
    """Reads `_socket` on a daemon thread, handing each read to `_receive_one`; `close` stops it and the socket."""

    def __init__(self, link_socket: socket.socket, thread_name: str):
        self._socket = link_socket
        self._socket.settimeout(RECEIVE_POLL_S)
        self._stop = threading.Event()
        self._thread = threading.Thread(target=self._receive_loop, name=thread_name, daemon=True)

    def start(self) -> None:
        self._thread.start()

    def close(self) -> None:
        self._stop.set()
        if self._thread.is_alive():
            self._thread.join(timeout=2 * RECEIVE_POLL_S + 1.0)
        self._socket.close()

    def _receive_one(self) -> None:
        """Reads and hands on one datagram or frame; raises socket.timeout or OSError as the socket does."""
        raise NotImplementedError

    def _receive_loop(self) -> None:
        while not self._stop.is_set():
            try:
                self._receive_one()
            except socket.timeout:
                continue
            except OSError:
                # Closed under us, or an ICMP port-unreachable echo of an earlier UDP send: keep listening.
                if self._stop.is_set():
                    return
                continue
