"""Checks before a verb writes its files (``post -o``, ``run -o``).

A job file is only ever written as a regular file: an existing directory,
FIFO, device or socket at the output path is refused (exit 2) before any
stage writes anything, so ``post -o /dev/ttyUSB0`` can never replace the
device node or stream into it unchecked.  A job with nothing to cut is
refused too: an empty ``job.nc`` would look like a finished job.
"""

from __future__ import annotations

from typing import Any

from ..core.errors import InputError

def check_output_path(path: str) -> None:
    """InputError when ``path`` exists and is not a regular file (checked before
    any stage runs; :func:`post.jobfile.refuse_special` is the one rule)."""
    from ..post.jobfile import refuse_special
    refuse_special(path)


def require_cut_items(result: Any, path: str) -> None:
    """InputError when the planned job (a ``JobResult``) cuts nothing."""
    if result.plan.items:
        return
    rec = result.recognition
    excluded = sum(1 for p in rec.parts if getattr(p, "excluded", False))
    raise InputError(f"nothing to cut: {len(rec.parts)} parts ({excluded} excluded), "
                     f"{len(rec.open_chains)} open chains, {len(result.drawing.marks)} marks; "
                     f"no job file is written", source=path)
