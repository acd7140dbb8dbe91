"""Compile the nesting engine's numba kernels once, at set-up (tools/setup.sh).

The kernels (``@njit(cache=True)`` in core/nesting: convex_kernel, overlap,
separation, compaction, hide_separation) compile in ~8 s on their first use after the
sources changed and are then loaded from numba's disk cache in well under a
second.  Without this step a user's first nest after ``bash bootstrap.sh``
would pay the compile inside its time budget.  Each kernel runs once on a
tiny real input: the module warm-ups (:func:`convex_sums.warm_up`,
:func:`hide_separation.warm_up`) and the strip separator on a row of two
L-shaped parts, set up as :mod:`strip_shrink` does.

Both numba cache folders a nest may use are filled: next to the sources
(numba's default) and the path planner's (``core.pathplan.jit``).

Exit status 0 when compiled, 3 when numba has no writable cache folder (the
caller then only prints a message: nothing is lost but the first run's
seconds).
"""

from __future__ import annotations

import os
import subprocess
import sys
import time

sys.path.insert(0, os.path.dirname(os.path.dirname(os.path.abspath(__file__))))


def _l_part(pid: str):
    from LeatherCutWorkbench.core.geometry import LineSeg
    from LeatherCutWorkbench.core.model import Contour, Part
    pts = [(0.0, 0.0), (40.0, 0.0), (40.0, 10.0), (10.0, 10.0), (10.0, 30.0), (0.0, 30.0)]
    segs = [LineSeg(pts[i], pts[(i + 1) % len(pts)]) for i in range(len(pts))]
    return Part(id=pid, outer=Contour(pid + "/o", segs), quantity=2)


def _row(parts):
    """Every copy at angle 0 in one loose row along the strip (a valid layout)."""
    from LeatherCutWorkbench.core.model import Container, Layout, Placement
    placements = [Placement(part_id=p.id, copy=k, container="strip", x=50.0 * (2 * i + k),
                            y=0.0, angle=0.0)
                  for i, p in enumerate(parts) for k in range(p.quantity)]
    return Layout(containers=[Container(id="strip", kind="strip", outline=[])],
                  placements=placements, metrics={"strip_length_mm": 200.0})


def main() -> int:
    t0 = time.monotonic()
    try:
        from LeatherCutWorkbench.core.nesting import ContainerSpec, NestOptions, convex_sums
        from LeatherCutWorkbench.core.nesting.hide_separation import warm_up
        from LeatherCutWorkbench.core.nesting.overlap import PairTable
        from LeatherCutWorkbench.core.nesting.separation import Separator
        from LeatherCutWorkbench.core.nesting.strip_shrink import _Instance, _compact
    except RuntimeError as exc:           # numba: "cannot cache function ... no locator"
        print(f"warm_jit: numba cannot cache its kernels ({exc})", file=sys.stderr)
        return 3
    parts = [_l_part("a"), _l_part("b")]
    opts = NestOptions(container=ContainerSpec.strip(60.0), workers=1)
    convex_sums.warm_up()
    inst = _Instance(_row(parts), parts, opts)
    sep = Separator(PairTable(inst.variants), inst.cb, inst.choices, inst.types, inst.y0, inst.y1,
                    inst.x0, inst.eps)
    sep.warm_up(inst.X, inst.Y, inst.V, inst.right_edge(inst.X, inst.V))
    _compact(sep, inst.X.copy(), inst.Y.copy(), inst.V)
    warm_up()
    print(f"warm_jit: nesting kernels ready in {time.monotonic() - t0:.1f} s"
          f" ({os.environ.get('NUMBA_CACHE_DIR') or 'next to the sources'})")
    if "NUMBA_CACHE_DIR" not in os.environ:
        # a process that imported the path planner first (the workbench) caches
        # the nesting kernels in the planner's folder instead: warm that one too
        from LeatherCutWorkbench.core.pathplan.jit import cache_dir
        os.environ["NUMBA_CACHE_DIR"] = cache_dir()
        return subprocess.run([sys.executable, os.path.abspath(__file__)]).returncode
    return 0


if __name__ == "__main__":
    sys.exit(main())
