"""Upper bounds on the utilisation of a hide instance, per number of hides.

    .venv/bin/python bench/hide_bounds.py bench/data/hides/Test2.json [...] [--used 0,1,2,3,4]

For k hides the best utilisation any layout that places every copy can reach
is item area / (the smallest total net area of k hides whose full-quality
material -- net area less the quality zones, which ``bench_nest_hides.py``
forbids to every item -- is at least the item area).  Exact over all
k-subsets (a few thousand for the Baldacci instances).  ``--used`` (hide
indices, e.g. PackingSolver's ``bins`` of a run) prints that set's net area
and utilisation too.  Areas in the file's units (mm^2 here): M = 10^6.
"""

from __future__ import annotations

import argparse
import itertools
import os
import sys
from dataclasses import replace
from typing import List, Optional, Sequence, Tuple

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, os.path.dirname(HERE))

from LeatherCutWorkbench.core.nesting.checker import part_polygon  # noqa: E402
from LeatherCutWorkbench.core.nesting.containers import net_area, usable_region  # noqa: E402
from LeatherCutWorkbench.core.nesting.esicup import read_esicup  # noqa: E402


def best_set(net: Sequence[float], usable: Sequence[float], items: float,
             k: int) -> Optional[Tuple[float, Tuple[int, ...]]]:
    """(net area, hide indices) of the k hides of least net area whose usable
    area holds ``items``; None when no k hides do."""
    best = None
    for c in itertools.combinations(range(len(net)), k):
        if sum(usable[i] for i in c) >= items:
            s = sum(net[i] for i in c)
            if best is None or s < best[0]:
                best = (s, c)
    return best


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("instances", nargs="+")
    ap.add_argument("--used", default=None, help="hide indices of a layout, comma-separated")
    a = ap.parse_args()
    for path in a.instances:
        inst = read_esicup(path)
        full = inst.hides[0].base_grade
        parts = [replace(p, grade=full) for p in inst.parts]
        items = sum(part_polygon(p, 0.1).area * p.quantity for p in parts)
        net: List[float] = [net_area(h) for h in inst.hides]
        usable = [usable_region(h, full).area for h in inst.hides]
        print(f"{os.path.basename(path)}: {sum(p.quantity for p in parts)} copies, "
              f"item area {items / 1e6:.2f} M, {len(net)} hides")
        for k in range(1, len(net) + 1):
            hit = best_set(net, usable, items, k)
            if hit is None:
                continue
            s, c = hit
            print(f"  k={k}: least net {s / 1e6:.1f} M -> at most {100 * items / s:.2f} % "
                  f"(fills {100 * items / sum(usable[i] for i in c):.1f} % of its usable "
                  f"area; hides {','.join(map(str, c))})")
        if a.used:
            used = [int(x) for x in a.used.split(",")]
            s = sum(net[i] for i in used)
            print(f"  set {a.used}: net {s / 1e6:.1f} M, {100 * items / s:.2f} %")


if __name__ == "__main__":
    main()
