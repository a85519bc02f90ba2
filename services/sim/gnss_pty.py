"""A pseudo-terminal carrying a simulated GNSS receiver's NMEA bytes, found through a symlink.

The slave end stays open here so writes never fail with EIO before (or between) readers opening it.
Raw mode so the line discipline passes the bytes unchanged (no CR/LF translation, no echo).
"""

from __future__ import annotations

import os
import tty
from pathlib import Path


class GnssPty:
    def __init__(self, link_path: str | Path) -> None:
        self.link_path = Path(link_path)
        self._master_fd, self._slave_fd = os.openpty()
        tty.setraw(self._master_fd)
        tty.setraw(self._slave_fd)
        self.device = os.ttyname(self._slave_fd)
        self.link_path.parent.mkdir(parents=True, exist_ok=True)
        if self.link_path.is_symlink() or self.link_path.exists():
            self.link_path.unlink()  # a stale link from an earlier run
        self.link_path.symlink_to(self.device)
        self.written = 0

    def write(self, data: bytes) -> int:
        """Writes all of data; returns the total bytes written to this line so far (the WireMark)."""
        view = memoryview(data)
        while view:
            sent = os.write(self._master_fd, view)
            view = view[sent:]
        self.written += len(data)
        return self.written

    def close(self) -> None:
        if self._master_fd < 0:
            return
        if self.link_path.is_symlink():
            self.link_path.unlink()
        os.close(self._master_fd)
        os.close(self._slave_fd)
        self._master_fd = self._slave_fd = -1

    def __enter__(self) -> GnssPty:
        return self

    def __exit__(self, *exc: object) -> None:
        self.close()
