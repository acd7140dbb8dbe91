"""Nesting benchmark: the own engine vs spyrrow (sparrow) on the ESICUP strip
instances, same time budget, one after the other on the same machine; plus a
leather hide job (100+ parts, irregular hide with defects and a quality zone).

    .venv/bin/python bench/bench_nest.py [--time 60] [--seed 1] [--instances albano,fu,...]
                                         [--no-sparrow] [--no-hide] [--workers 2]

Every layout is re-checked with the independent checker (no overlap, inside
the strip, allowed rotations only) before its density is reported.  Instances
are read from /work/shared/bench/nesting/ when present, else from
tests/data/nest/.  Prints Markdown tables.
"""

from __future__ import annotations

import argparse
import math
import os
import sys
import time

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, os.path.dirname(HERE))

from LeatherCutWorkbench.core.geometry import ArcSeg, LineSeg  # noqa: E402
from LeatherCutWorkbench.core.model import Container, Contour, Part  # noqa: E402
from LeatherCutWorkbench.core.nesting import (ContainerSpec, NestOptions, check_layout,  # noqa: E402
                                              nest)
from LeatherCutWorkbench.core.nesting.esicup import read_esicup  # noqa: E402

SHARED = "/work/shared/bench/nesting"
LOCAL = os.path.join(os.path.dirname(HERE), "tests", "data", "nest")
#: spyrrow 60 s / 2-core reference densities measured for the fact sheet (seed 42; fu and
#: shirts: mean of seeds 42 / 7 / 123), shown for orientation only.
FACT_SHEET = {"albano": 87.26, "fu": 88.45, "shapes0": 64.47, "shirts": 85.84}


def instance_path(name: str) -> str:
    for d in (SHARED, LOCAL):
        p = os.path.join(d, f"{name}.json")
        if os.path.exists(p):
            return p
    raise SystemExit(f"instance {name} not found in {SHARED} or {LOCAL}")


def run_strip(name: str, engine: str, budget: float, seed: int, workers: int):
    inst = read_esicup(instance_path(name))
    opts = NestOptions(container=ContainerSpec.strip(inst.strip_height), time_budget=budget,
                       seed=seed, workers=workers, engine=engine)
    t0 = time.monotonic()
    lay = nest(inst.parts, opts)
    wall = time.monotonic() - t0
    problems = check_layout(inst.parts, lay)
    ok = not problems and not lay.unplaced
    return 100.0 * lay.metrics["density"], lay.metrics["strip_length_mm"], wall, ok, lay.metrics


def _poly(pid, pts):
    return Contour(pid, [LineSeg(pts[i], pts[(i + 1) % len(pts)]) for i in range(len(pts))])


def hide_job():
    """A 2.2 x 1.5 m hide-like outline (2.2 m2), 6 defects, a grade-3 back zone,
    and 104 shoe / bag parts (vamps, L-shapes, frames with holes, discs, straps)."""
    pts = []
    for i in range(72):
        a = 2 * math.pi * i / 72
        r = 1.0 + 0.10 * math.sin(3 * a) + 0.06 * math.cos(5 * a) + 0.04 * math.sin(7 * a + 1)
        pts.append((1100 + 1000 * r * math.cos(a), 800 + 700 * r * math.sin(a)))
    defects = []
    for k, (cx, cy, rr) in enumerate([(600, 800, 35), (1300, 1100, 25), (1600, 500, 45),
                                      (1000, 400, 20), (800, 1250, 30), (1750, 950, 28)]):
        defects.append([(cx + rr * math.cos(2 * math.pi * j / 16), cy + rr * math.sin(2 * math.pi * j / 16))
                        for j in range(16)])
    zone = [(400, 550), (1800, 550), (1800, 1050), (400, 1050)]
    hide = Container(id="hide1", kind="hide", outline=pts, defects=defects, zones=[(3, zone)],
                     base_grade=1)
    parts = []

    def add(p):
        parts.append(p)

    for i in range(6):
        w, h = 320 + 20 * i, 180 + 10 * i
        add(Part(id=f"vamp{i}", outer=_poly(f"v{i}", [(0, 0), (w, 0), (w, h * 0.7), (w * 0.6, h), (0, h)]),
                 quantity=2, rotations=[0, 180], grade=3, mirror_allowed=True))
    for i in range(5):
        add(Part(id=f"L{i}", outer=_poly(f"l{i}", [(0, 0), (220, 0), (220, 60), (70, 60), (70, 160), (0, 160)]),
                 quantity=4, rotations=[0, 90, 180, 270]))
    for i in range(4):
        w, h = 140 + 30 * i, 90 + 10 * i
        add(Part(id=f"panel{i}", outer=_poly(f"p{i}", [(0, 0), (w, 0), (w, h), (0, h)]),
                 holes=[_poly(f"ph{i}", [(20, 20), (20, h - 20), (w - 20, h - 20), (w - 20, 20)])],
                 quantity=4, rotations=[0, 180]))
    for i in range(4):
        r = 30 + 8 * i
        add(Part(id=f"disc{i}", outer=Contour(f"d{i}", [ArcSeg((r, r), r, 0, 360)]), quantity=8,
                 rotations=[0]))
    for i in range(6):
        add(Part(id=f"strap{i}", outer=_poly(f"s{i}", [(0, 0), (300 + 20 * i, 0), (300 + 20 * i, 35), (0, 35)]),
                 quantity=4, rotations=[0, 180]))
    return hide, parts


def run_hide(budget: float, seed: int, workers: int):
    hide, parts = hide_job()
    opts = NestOptions(container=ContainerSpec.hide(hide), spacing=2, margin=5, time_budget=budget,
                       seed=seed, workers=workers)
    t0 = time.monotonic()
    lay = nest(parts, opts)
    wall = time.monotonic() - t0
    ok = not check_layout(parts, lay, spacing=2, margin=5) and \
        not any(f.code == "invalid-placement-removed" for f in lay.findings)
    return parts, lay, wall, ok


def main() -> int:
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--time", type=float, default=60.0)
    ap.add_argument("--seed", type=int, default=1)
    ap.add_argument("--sparrow-seed", type=int, default=42)
    ap.add_argument("--workers", type=int, default=2)
    ap.add_argument("--instances", default="albano,fu,shapes0,shirts")
    ap.add_argument("--no-sparrow", action="store_true")
    ap.add_argument("--no-hide", action="store_true")
    a = ap.parse_args()
    print(f"load average at start: {os.getloadavg()[0]:.2f} (2 cores)\n")
    print("| instance | own density % | own length | own wall s | own layouts tried | "
          "spyrrow density % | spyrrow length | spyrrow wall s | ratio own/spyrrow | "
          "fact-sheet spyrrow 60 s % |")
    print("|---|---|---|---|---|---|---|---|---|---|")
    ratios = []
    for name in a.instances.split(","):
        d, L, w, ok, mo = run_strip(name, "own", a.time, a.seed, a.workers)
        ev = mo.get("evaluations", 0)
        own = f"{d:.2f}" + ("" if ok else " INVALID")
        if a.no_sparrow:
            print(f"| {name} | {own} | {L:.3f} | {w:.1f} | {ev} | - | - | - | - | {FACT_SHEET[name]} |",
                  flush=True)
            continue
        ds, Ls, ws, oks, _ = run_strip(name, "sparrow", a.time, a.sparrow_seed, a.workers)
        ratio = d / ds
        ratios.append(ratio)
        sp = f"{ds:.2f}" + ("" if oks else " INVALID")
        print(f"| {name} | {own} | {L:.3f} | {w:.1f} | {ev} | {sp} | {Ls:.3f} | {ws:.1f} | "
              f"**{ratio:.3f}** | {FACT_SHEET[name]} |", flush=True)
    if ratios:
        print(f"\nminimum ratio {min(ratios):.3f} (target >= 0.95 on every instance)")
    if not a.no_hide:
        parts, lay, wall, ok = run_hide(a.time, a.seed, a.workers)
        m = lay.metrics
        n = sum(p.quantity for p in parts)
        print("\n| hide job | copies | placed | unplaced | utilisation (net of defects) % | "
              "utilisation (gross outline) % | wall s | valid |")
        print("|---|---|---|---|---|---|---|---|")
        print(f"| 2.2 x 1.5 m hide, 6 defects, grade-3 zone, spacing 2, margin 5 | {n} | "
              f"{m['placed_count']} | {m['unplaced_count']} | {100 * m['utilisation']:.2f} | "
              f"{100 * m['utilisation_gross']:.2f} | {wall:.1f} | {'yes' if ok else 'NO'} |")
    print(f"\nload average at end: {os.getloadavg()[0]:.2f}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
