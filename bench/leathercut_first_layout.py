"""``leathercut`` that also reports when the first valid layout appeared.

    PYTHONPATH=ROOT ROOT/.venv/bin/python bench/leathercut_first_layout.py nest ... --json

Runs the CLI of the checkout on ``PYTHONPATH`` unchanged, except that the
progress callback given to ``core.nesting.nest`` is wrapped: the first
message naming a best layout ("best: ...", sent by the engine's parent
process as soon as a worker's first layout reaches it) writes one line
``first-layout-s S`` to stderr, S = seconds since the process started (the
CLI's own budget start).  Works with any version of the engine that reports
its best-so-far that way, so old and new code are measured alike.  (The
file name starts with ``leathercut`` so the CLI counts its budget from the
process start, as the installed script does.)
"""

from __future__ import annotations

import sys
import time

from LeatherCutWorkbench.cli import main
from LeatherCutWorkbench.core import nesting

_nest = nesting.nest


def _nest_timed(parts, options, progress=None, on_best=None, stop=None):
    start = options.started_at if options.started_at is not None else time.monotonic()
    seen = []

    def wrapped(frac: float, msg: str) -> bool:
        if not seen and msg.startswith("best:"):
            seen.append(time.monotonic() - start)
            sys.stderr.write(f"first-layout-s {seen[0]:.3f}\n")
            sys.stderr.flush()
        return True if progress is None else progress(frac, msg)

    return _nest(parts, options, wrapped, on_best, stop)


nesting.nest = _nest_timed

if __name__ == "__main__":
    sys.exit(main())
