"""Profile one exact bottom-left fill of a Baldacci hide instance (one core).

    .venv/bin/python bench/profile_hide_fill.py [bench/data/hides/Test2.json] [--hides 5] [--top 25]

The fill the engine's workers start with on hides: every copy, largest
first, on the k smallest hides first (``hide_choice.tight_order``), zones
and holes forbidden to every part and rotations every 30 degrees (as in
``bench_nest_hides.py``).  Prints the fill's wall time, the unplaced copies,
the time of the same fill again with every no-fit polygon and inner-fit
region cached, and cProfile's top lines by cumulative time.
"""

from __future__ import annotations

import argparse
import cProfile
import os
import pstats
import sys
import time
from dataclasses import replace

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, os.path.dirname(HERE))

from LeatherCutWorkbench.core.nesting import ContainerSpec, NestOptions  # noqa: E402
from LeatherCutWorkbench.core.nesting.engine import prepare  # noqa: E402
from LeatherCutWorkbench.core.nesting.esicup import read_esicup  # noqa: E402
from LeatherCutWorkbench.core.nesting.hide_choice import tight_order, used_positions  # noqa: E402
from LeatherCutWorkbench.core.nesting.search import start_orders  # noqa: E402

ANGLES = [float(a) for a in range(0, 360, 30)]


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("instance", nargs="?", default=os.path.join(HERE, "data", "hides", "Test2.json"))
    ap.add_argument("--hides", type=int, default=5)
    ap.add_argument("--top", type=int, default=25)
    a = ap.parse_args()
    inst = read_esicup(a.instance)
    full = inst.hides[0].base_grade
    parts = [replace(p, grade=full, grade_regions=[]) for p in inst.parts]
    opts = NestOptions(container=ContainerSpec.hide(*inst.hides), time_budget=60, workers=1,
                       rotations_override=ANGLES)
    t0 = time.monotonic()
    _types, variants, problem, copies, _hides, _scale = prepare(parts, opts)
    print(f"{len(copies)} copies, {len(variants)} orientations, prepared in "
          f"{time.monotonic() - t0:.2f} s; load {os.getloadavg()[0]:.1f}")
    placer = problem.placer()
    placer.bin_order = tight_order(problem.hide_net, a.hides)
    seq = start_orders(problem, copies)[0]
    prof = cProfile.Profile()
    t0 = time.monotonic()
    prof.enable()
    tr = placer.place(seq, abortable=False)
    prof.disable()
    print(f"fill {time.monotonic() - t0:.2f} s (profiled), unplaced {len(tr.unplaced)}, "
          f"hides used {len(used_positions(tr.placements))}")
    t0 = time.monotonic()
    placer.place(seq, abortable=False)
    print(f"same fill, everything cached: {time.monotonic() - t0:.2f} s")
    pstats.Stats(prof).sort_stats("cumulative").print_stats(a.top)


if __name__ == "__main__":
    main()
