"""The GNSS receiver's port, read with pyserial: a device path or a pyserial URL (`/dev/ttyACM0`,
`socket://host:port` for receivers that stream NMEA over TCP, `rfc2217://host:port`).

Two ways to read: `read_until(total)` for lockstep runs, where the simulator announces how many bytes it has
written (gnss/serial_mark) and the reader catches up to exactly that many; `start_thread(on_chunk)` on the
vehicle, where a daemon thread hands every chunk on as it arrives. When the port drops (a USB receiver
unplugged, a pty closed, a TCP stream ended) the thread says so once, counts it and reopens the port until
it is back: it never dies silently.
"""

from __future__ import annotations

import logging
import os
import threading
import time
from collections import Counter
from typing import Callable

import serial

from coopdrive.runtime.service import HardwareUnavailable

OPEN_POLL_S = 0.05
READ_TIMEOUT_S = 0.1  # pyserial read timeout: how often the reader thread checks for stop
READ_CHUNK_BYTES = 4096
REOPEN_INTERVAL_S = 1.0
PORT_ERRORS = (serial.SerialException, OSError, TypeError, AttributeError)


class GnssPortError(HardwareUnavailable):
    pass


def _is_url(port: str) -> bool:
    return "://" in port


class GnssSerial:
    def __init__(self, port: str, baudrate: int = 115200, open_timeout_s: float = 10.0,
                 log: logging.Logger | None = None, reopen_interval_s: float = REOPEN_INTERVAL_S) -> None:
        """Raises GnssPortError (one line naming the port) when it cannot be opened within open_timeout_s."""
        self.port = port
        self.baudrate = baudrate
        self.log = log or logging.getLogger("coopdrive.geolocation")
        self.reopen_interval_s = reopen_interval_s
        self.counters: Counter[str] = Counter()  # gnss_port_drops, gnss_port_reopens
        deadline = time.monotonic() + open_timeout_s
        # The simulator may create the port (a pty symlink) after this service starts.
        while not _is_url(port) and not os.path.exists(port):
            if time.monotonic() >= deadline:
                raise GnssPortError(f"GNSS port {port} did not appear within {open_timeout_s:g} s")
            time.sleep(OPEN_POLL_S)
        self._serial = self._open()
        self.read_total = 0
        self._stop = threading.Event()
        self._thread: threading.Thread | None = None

    def _open(self) -> serial.SerialBase:
        try:
            return serial.serial_for_url(self.port, self.baudrate, timeout=READ_TIMEOUT_S)
        except (serial.SerialException, OSError, ValueError) as error:
            reason = str(error).splitlines()[0] if str(error) else type(error).__name__
            raise GnssPortError(f"GNSS port {self.port} could not be opened: {reason}") from error

    def read_until(self, total_bytes: int, timeout_s: float, on_chunk: Callable[[bytes], None]) -> bool:
        """Reads until read_total reaches total_bytes, passing each chunk on; False on timeout, or when the port
        fails (its writer gone, as a simulator that has ended): said in one line, counted as a drop."""
        deadline = time.monotonic() + timeout_s
        while self.read_total < total_bytes:
            remaining_s = deadline - time.monotonic()
            if remaining_s <= 0.0:
                return False
            try:
                self._serial.timeout = min(READ_TIMEOUT_S, remaining_s)
                # Never read past the mark: the next epoch's bytes belong to the next mark's step.
                chunk = self._serial.read(total_bytes - self.read_total)
            except PORT_ERRORS as error:
                self.counters["gnss_port_drops"] += 1
                self.log.warning("GNSS port %s failed while reading up to byte %d: %s", self.port, total_bytes,
                                 str(error).splitlines()[0] if str(error) else type(error).__name__)
                return False
            if chunk:
                self.read_total += len(chunk)
                on_chunk(chunk)
        return True

    def skip_to(self, total_bytes: int) -> int:
        """After a timed-out mark: count the missing bytes as lost (e.g. written before we opened the port,
        which pyserial flushes on open) so later marks line up again. Returns how many were skipped."""
        skipped = max(0, total_bytes - self.read_total)
        self.read_total += skipped
        return skipped

    def start_thread(self, on_chunk: Callable[[bytes], None]) -> None:
        """Free running: a daemon thread calls on_chunk(bytes) for every chunk (on the thread: hand it on)."""
        self._thread = threading.Thread(target=self._run, args=(on_chunk,), name=f"gnss-serial {self.port}",
                                        daemon=True)
        self._thread.start()

    def _run(self, on_chunk: Callable[[bytes], None]) -> None:
        while not self._stop.is_set():
            try:
                chunk = self._serial.read(max(1, min(READ_CHUNK_BYTES, self._serial.in_waiting)))
            except PORT_ERRORS as error:
                if self._stop.is_set():
                    return
                self._dropped(error)
                continue
            if chunk:
                self.read_total += len(chunk)
                on_chunk(chunk)

    def _dropped(self, error: Exception) -> None:
        """The port went away: say so once, then try to reopen it until it is back or we stop."""
        self.counters["gnss_port_drops"] += 1
        self.log.warning("GNSS port %s dropped (%s); reopening every %g s", self.port,
                         str(error).splitlines()[0] if str(error) else type(error).__name__, self.reopen_interval_s)
        try:
            self._serial.close()
        except PORT_ERRORS:
            pass
        while not self._stop.wait(self.reopen_interval_s):
            if not _is_url(self.port) and not os.path.exists(self.port):
                continue
            try:
                self._serial = self._open()
            except GnssPortError:
                continue
            self.counters["gnss_port_reopens"] += 1
            self.log.warning("GNSS port %s reopened", self.port)
            return

    def close(self) -> None:
        self._stop.set()
        if self._thread is not None:
            self._thread.join(timeout=2 * READ_TIMEOUT_S + self.reopen_interval_s + 1.0)
        try:
            self._serial.close()
        except PORT_ERRORS:
            pass
