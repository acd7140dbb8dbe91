"""One sender per port: an exclusive lock file next to the serial device lock.

Two senders on one port steal each other's replies (one took the other's
``$I`` answer).  :class:`PortLock` takes ``fcntl.flock(LOCK_EX | LOCK_NB)`` on
``<tmp>/leathercut-<port>.lock`` (per open file, so it also separates two
links inside one process); :class:`~.grbl.GrblLink` additionally opens device
paths with pyserial's ``exclusive=True`` (``flock`` on the device itself, which
keeps out other programs that honour it).  The lock is released when the link
closes or the process ends (the kernel drops ``flock`` locks with the file).
On systems without ``fcntl`` only pyserial's own exclusivity applies.
"""

from __future__ import annotations

import os
import re
import tempfile
import weakref
from typing import Optional

from ...core.errors import LeatherCutError

try:
    import fcntl
except ImportError:           # Windows: COM ports are exclusive by the OS already
    fcntl = None


class PortBusy(LeatherCutError):
    """Another LeatherCut sender holds the port."""


def lock_path(url: str) -> str:
    """The lock file for ``url``: device paths by their real path."""
    key = os.path.realpath(url) if "://" not in url else url
    name = re.sub(r"[^A-Za-z0-9_.-]+", "_", key).strip("_") or "port"
    return os.path.join(tempfile.gettempdir(), f"leathercut-{name}.lock")


class PortLock:
    def __init__(self, url: str):
        self.url = url
        self.path = lock_path(url)
        self._fd: Optional[int] = None

    def acquire(self) -> "PortLock":
        if fcntl is None:
            return self
        try:
            fd = os.open(self.path, os.O_RDWR | os.O_CREAT, 0o666)
        except OSError:
            return self               # no writable temp folder: pyserial's lock only
        try:
            fcntl.flock(fd, fcntl.LOCK_EX | fcntl.LOCK_NB)
        except OSError:
            os.close(fd)
            raise PortBusy(f"the port is in use by another LeatherCut sender (lock "
                           f"{self.path})", source=self.url)
        os.ftruncate(fd, 0)
        os.write(fd, f"{os.getpid()}\n".encode())
        self._fd = fd
        # a link dropped without close() must not hold the port for the process's life
        self._final = weakref.finalize(self, _close_quietly, fd)
        return self

    def release(self) -> None:
        if self._fd is not None:
            self._final.detach()
            _close_quietly(self._fd)
            self._fd = None


def _close_quietly(fd: int) -> None:
    try:
        os.close(fd)                   # closing the file drops its flock
    except OSError:
        pass
