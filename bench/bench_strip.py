"""Strip benchmark: the own engine with the strip improvement phase
(core/nesting/strip_shrink.py) vs spyrrow (sparrow) on the ESICUP strip
instances, same time budget, one after the other in the same run.

    .venv/bin/python bench/bench_strip.py [--times 10,60] [--seed 1] [--sparrow-seed 42]
                                          [--instances albano,fu,shapes0,shirts] [--workers 2]

"own+phase" is :func:`strip_shrink.nest_compacted`: the engine's search for
SEARCH_SHARE of the budget (less with many copies), then the overlap-minimisation
phase until the budget ends.  Every layout is re-checked with the independent checker (no
overlap, inside the strip, allowed rotations only, every copy placed) before
its density is reported.  Wall and CPU seconds (this process + its worker
processes) are given per run.  Prints a Markdown table.
"""

from __future__ import annotations

import argparse
import os
import resource
import sys
import time

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, os.path.dirname(HERE))

from LeatherCutWorkbench.core.nesting import ContainerSpec, NestOptions, check_layout, nest  # noqa: E402
from LeatherCutWorkbench.core.nesting.esicup import read_esicup  # noqa: E402
from LeatherCutWorkbench.core.nesting.strip_shrink import nest_compacted  # noqa: E402

from bench_nest import instance_path  # noqa: E402


def _cpu() -> float:
    s, c = resource.getrusage(resource.RUSAGE_SELF), resource.getrusage(resource.RUSAGE_CHILDREN)
    return s.ru_utime + s.ru_stime + c.ru_utime + c.ru_stime


def run(name: str, engine: str, budget: float, seed: int, workers: int):
    """(density %, length, wall s, CPU s, valid) of one run."""
    inst = read_esicup(instance_path(name))
    opts = NestOptions(container=ContainerSpec.strip(inst.strip_height), time_budget=budget,
                       seed=seed, workers=workers, engine=engine)
    c0, t0 = _cpu(), time.monotonic()
    lay = nest_compacted(inst.parts, opts) if engine == "own" else nest(inst.parts, opts)
    wall, cpu = time.monotonic() - t0, _cpu() - c0
    ok = not check_layout(inst.parts, lay) and not lay.unplaced
    return 100.0 * lay.metrics["density"], lay.metrics["strip_length_mm"], wall, cpu, ok


def main() -> int:
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--times", default="10,60")
    ap.add_argument("--seed", type=int, default=1)
    ap.add_argument("--sparrow-seed", type=int, default=42)
    ap.add_argument("--workers", type=int, default=2)
    ap.add_argument("--instances", default="albano,fu,shapes0,shirts")
    a = ap.parse_args()
    print(f"load average at start: {os.getloadavg()[0]:.2f} (2 cores)\n")
    print("| instance | T s | own+phase density % | length | wall s | CPU s | "
          "spyrrow density % | length | wall s | CPU s | ratio |")
    print("|---|---|---|---|---|---|---|---|---|---|---|")
    for t in [float(v) for v in a.times.split(",")]:
        for name in a.instances.split(","):
            d, L, w, c, ok = run(name, "own", t, a.seed, a.workers)
            ds, Ls, ws, cs, oks = run(name, "sparrow", t, a.sparrow_seed, a.workers)
            own = f"{d:.2f}" + ("" if ok else " INVALID")
            sp = f"{ds:.2f}" + ("" if oks else " INVALID")
            print(f"| {name} | {t:g} | {own} | {L:.3f} | {w:.1f} | {c:.1f} | {sp} | {Ls:.3f} | "
                  f"{ws:.1f} | {cs:.1f} | **{d / ds:.3f}** |", flush=True)
    print(f"\nload average at end: {os.getloadavg()[0]:.2f}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
