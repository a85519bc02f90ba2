"""The GNSS receiver's serial port, read with pyserial.

Two ways to read: `read_until(total)` for lockstep runs, where the simulator announces how many bytes it has
written (gnss/serial_mark) and the reader catches up to exactly that many; `start_thread(on_chunk)` on the
vehicle, where a daemon thread hands every chunk on as it arrives.
"""

from __future__ import annotations

import os
import threading
import time
from typing import Callable

import serial

OPEN_POLL_S = 0.05
READ_TIMEOUT_S = 0.1  # pyserial read timeout: how often the reader thread checks for stop
READ_CHUNK_BYTES = 4096


class GnssPortError(RuntimeError):
    pass


class GnssSerial:
    def __init__(self, port: str, baudrate: int = 115200, open_timeout_s: float = 10.0) -> None:
        self.port = port
        deadline = time.monotonic() + open_timeout_s
        # The simulator may create the port (a pty symlink) after this service starts.
        while not os.path.exists(port):
            if time.monotonic() >= deadline:
                raise GnssPortError(f"GNSS serial port {port} did not appear within {open_timeout_s:g} s")
            time.sleep(OPEN_POLL_S)
        try:
            self._serial = serial.Serial(port, baudrate, timeout=READ_TIMEOUT_S)
        except (serial.SerialException, OSError) as error:
            raise GnssPortError(f"GNSS serial port {port} could not be opened: {error}") from error
        self.read_total = 0
        self._stop = threading.Event()
        self._thread: threading.Thread | None = None

    def read_until(self, total_bytes: int, timeout_s: float, on_chunk: Callable[[bytes], None]) -> bool:
        """Reads until read_total reaches total_bytes, passing each chunk on; False on timeout."""
        deadline = time.monotonic() + timeout_s
        while self.read_total < total_bytes:
            remaining_s = deadline - time.monotonic()
            if remaining_s <= 0.0:
                return False
            self._serial.timeout = min(READ_TIMEOUT_S, remaining_s)
            # Never read past the mark: the next epoch's bytes belong to the next mark's step.
            chunk = self._serial.read(total_bytes - self.read_total)
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
            except (serial.SerialException, OSError, TypeError):
                if self._stop.is_set():
                    return
                raise
            if chunk:
                self.read_total += len(chunk)
                on_chunk(chunk)

    def close(self) -> None:
        self._stop.set()
        if self._thread is not None:
            self._thread.join(timeout=2 * READ_TIMEOUT_S + 1.0)
        self._serial.close()
