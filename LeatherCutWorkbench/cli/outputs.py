"""Checks before a verb writes its files (``post -o``, ``run -o``).

A job file is only ever written as a regular file: an existing directory,
FIFO, device or socket at the output path is refused (exit 2) before any
stage writes anything, so ``post -o /dev/ttyUSB0`` can never replace the
device node or stream into it unchecked.  A job with nothing to cut is
refused too: an empty ``job.nc`` would look like a finished job.
"""

from __future__ import annotations

import os
import stat
from typing import Any

from ..core.errors import InputError

_KINDS = ((stat.S_ISDIR, "a directory"), (stat.S_ISFIFO, "a FIFO (named pipe)"),
          (stat.S_ISCHR, "a character device"), (stat.S_ISBLK, "a block device"),
          (stat.S_ISSOCK, "a socket"))


def check_output_path(path: str) -> None:
    """InputError when ``path`` exists and is not a regular file."""
    try:
        mode = os.stat(path).st_mode
    except FileNotFoundError:
        return
    except OSError as exc:
        raise InputError(f"cannot write: {exc.strerror or exc}", source=path) from exc
    if stat.S_ISREG(mode):
        return
    what = next((w for test, w in _KINDS if test(mode)), "not a regular file")
    raise InputError(f"is {what}: job files are only written as regular files", source=path)


def require_cut_items(result: Any, path: str) -> None:
    """InputError when the planned job (a ``JobResult``) cuts nothing."""
    if result.plan.items:
        return
    rec = result.recognition
    excluded = sum(1 for p in rec.parts if getattr(p, "excluded", False))
    raise InputError(f"nothing to cut: {len(rec.parts)} parts ({excluded} excluded), "
                     f"{len(rec.open_chains)} open chains, {len(result.drawing.marks)} marks; "
                     f"no job file is written", source=path)
