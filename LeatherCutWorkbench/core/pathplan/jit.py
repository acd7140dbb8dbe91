"""numba set-up for the compiled search kernels (:mod:`.kernels`).

The memetic search runs millions of scalar moves (2-opt, Or-opt, insertions,
the entry DP) per second; numpy cannot vectorise such branchy pointer work and
plain Python is ~100x slower, so the kernels are compiled with numba.  The
compiled machine code is cached on disk (``cache=True``) in a per-user folder
-- ``$NUMBA_CACHE_DIR`` when set, else ``$XDG_CACHE_HOME/leathercut/numba``
(default ``~/.cache/leathercut/numba``) -- so only the very first plan on a
machine pays the compile time; later processes load the cache in well under a
second.  ``nogil=True`` lets the islands of the search run on several cores
from plain Python threads.
"""

from __future__ import annotations

import os


def cache_dir() -> str:
    """Folder of the on-disk JIT cache (created on first use by numba)."""
    env = os.environ.get("NUMBA_CACHE_DIR")
    if env:
        return env
    base = os.environ.get("XDG_CACHE_HOME") or os.path.join(os.path.expanduser("~"), ".cache")
    return os.path.join(base, "leathercut", "numba")


os.environ.setdefault("NUMBA_CACHE_DIR", cache_dir())

import numba  # noqa: E402  (the cache folder must be set before numba reads its config)

numba.config.CACHE_DIR = cache_dir()


def njit(fn):
    """``numba.njit`` with the project's settings: cached, GIL released."""
    return numba.njit(cache=True, nogil=True)(fn)
