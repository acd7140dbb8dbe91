"""Hide benchmark: the own engine vs PackingSolver on Baldacci leather hides.

    .venv/bin/python bench/bench_nest_hides.py [--time 60] [--instances bench/data/hides/*.json]
        [--packingsolver-python /path/to/venv312/bin/python] [--workers 2] [--repeat 1]

Instances are jagua-rs bin-packing JSON files (``leathercut nest --esicup``
reads them).  PackingSolver (fontanf, PyPI ``packingsolver``, Python >= 3.12)
is never a product dependency: give the interpreter of a separate venv with
``--packingsolver-python``; it runs in a child process with the same time
limit.  Its Python builder has no quality rules, so for a like-for-like
comparison both engines get the *same* simplified problem: holes and
quality-1 zones are forbidden to every item (``--zones forbidden``, the
default); ``--zones graded`` runs the own engine with the file's qualities
(items with ``min_quality`` 1 may use the zones) and PackingSolver is then
skipped.  Rotations: every 30 degrees for both.  Objective: as many item
area as fits (knapsack) when the hides cannot hold every item, else fewest
hides.  Utilisation = placed item area / net area (outline minus holes) of
the hides used.  Every own layout is re-checked by the independent checker.
``--repeat N``: N own runs per instance (PackingSolver once, after the
first), to see the run-to-run spread.  Column *dropped*: copies the
engine's own final check took out of the search's layout (invalid
placements, each named in an ``invalid-placement-removed`` finding; they
count as unplaced; "best replaced": the engine kept an earlier valid layout
instead, ``invalid-layout-replaced``) -- 0 unless the search has a defect.
Prints one Markdown table row per instance and engine run.
"""

from __future__ import annotations

import argparse
import glob
import json
import os
import subprocess
import sys
import time
from dataclasses import replace

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, os.path.dirname(HERE))

from LeatherCutWorkbench.core.nesting import (ContainerSpec, NestOptions, check_layout,  # noqa: E402
                                              nest)
from LeatherCutWorkbench.core.nesting.containers import net_area  # noqa: E402
from LeatherCutWorkbench.core.nesting.esicup import read_esicup  # noqa: E402

ANGLES = [float(a) for a in range(0, 360, 30)]


def run_own(path: str, budget: float, workers: int, graded: bool):
    inst = read_esicup(path)
    parts = inst.parts
    hides = inst.hides
    if not graded:                 # zones forbidden to everyone, as for PackingSolver
        full = hides[0].base_grade
        parts = [replace(p, grade=full, grade_regions=[]) for p in parts]
    opts = NestOptions(container=ContainerSpec.hide(*hides), time_budget=budget, workers=workers,
                       rotations_override=ANGLES)
    t0 = time.monotonic()
    lay = nest(parts, opts)
    wall = time.monotonic() - t0
    problems = check_layout(parts, lay, rotations_override=ANGLES)
    m = lay.metrics
    dropped = len({f.message.split(" ", 1)[0] for f in lay.findings
                   if f.code == "invalid-placement-removed"})
    replaced = any(f.code == "invalid-layout-replaced" for f in lay.findings)
    return {"engine": "own", "wall_s": wall, "hides_used": m["hides"],
            "dropped": f"{dropped}{', best replaced' if replaced else ''}",
            "hides": len(hides), "placed": m["placed_count"],
            "copies": sum(p.quantity for p in parts), "item_area": m["item_area_mm2"],
            "utilisation": m["utilisation"], "valid": not problems,
            "per_hide": [round(c["utilisation"], 4) for c in m["per_container"]]}


#: the child script: reads the instance JSON itself, answers one JSON line
PS_SCRIPT = r'''
import json, sys, time
from packingsolver import irregular as ir
import packingsolver
path, budget = sys.argv[1], float(sys.argv[2])
d = json.load(open(path))
snake = "bins" in d
items = d["items"] if snake else d["Items"]
bins = d["bins"] if snake else d["Objects"]
def rings(shape):
    if snake:
        s = shape["data"]
        return (s, []) if shape["type"] == "simple_polygon" else (s["outer"], s.get("inner", []))
    return shape["Outer"], shape.get("Inner", [])
def poly(r):
    r = [tuple(p) for p in r]
    if r[0] == r[-1]:
        r = r[:-1]
    twice_area = sum(x0 * y1 - x1 * y0 for (x0, y0), (x1, y1) in zip(r, r[1:] + r[:1]))
    if twice_area < 0:             # PackingSolver rejects clockwise rings (Scarpa's zones)
        r = r[::-1]
    return ir.build_shape([list(p) for p in r])
def swh(r):
    s = ir.ShapeWithHoles(); s.shape = poly(r); return s
b = ir.InstanceBuilder()
b.set_objective(getattr(packingsolver.Objective, sys.argv[3]))
rot = [(a, a, False) for a in range(0, 360, 30)]
for it in items:
    outer, _ = rings(it["shape"] if snake else it["Shape"])
    b.add_item_type(swh(outer), allowed_rotations=rot,
                    copies=int(it.get("demand", it.get("Demand", 1))))
for bn in bins:
    outer, inner = rings(bn["shape"] if snake else bn["Shape"])
    bt = b.add_bin_type(poly(outer), copies=int(bn.get("stock", bn.get("Stock", 1))))
    for h in inner:
        b.add_defect(bt, 0, swh(h))
    for z in bn.get("zones", bn.get("Zones", [])):
        zo, _ = rings(z["shape"] if snake else z["Shape"])
        b.add_defect(bt, 1, swh(zo))
inst = b.build()
p = ir.OptimizeParameters()
p.time_limit = budget
p.verbosity_level = 0
t0 = time.monotonic()
out = ir.optimize(inst, p)
sol = out.solution
used = [sb.bin_type_id for sb in [sol.bin(i) for i in range(sol.number_of_different_bins())]
        for _ in range(sb.copies)]
print(json.dumps({"wall_s": time.monotonic() - t0, "item_area": sol.item_area(),
                  "placed": sol.number_of_items(), "bins": used, "feasible": sol.feasible()}))
'''


def run_packingsolver(python: str, path: str, budget: float, objective: str):
    inst = read_esicup(path)
    nets = {}
    k = 0
    raw = json.load(open(path))
    for n, bn in enumerate(raw.get("bins", raw.get("Objects", []))):
        stock = int(bn.get("stock", bn.get("Stock", 1)))
        nets[n] = net_area(inst.hides[k])
        k += stock
    t0 = time.monotonic()
    r = subprocess.run([python, "-c", PS_SCRIPT, path, str(budget), objective],
                       capture_output=True, text=True, timeout=budget * 3 + 60)
    wall = time.monotonic() - t0
    if r.returncode != 0:
        return {"engine": "packingsolver", "error": r.stderr.strip().splitlines()[-1:]}
    d = json.loads(r.stdout.strip().splitlines()[-1])
    net = sum(nets[b] for b in d["bins"])
    return {"engine": "packingsolver", "wall_s": wall, "hides_used": len(d["bins"]),
            "hides": len(inst.hides), "placed": d["placed"],
            "copies": sum(p.quantity for p in inst.parts), "item_area": d["item_area"],
            "utilisation": d["item_area"] / net if net else 0.0, "valid": d["feasible"],
            "per_hide": [], "dropped": ""}


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--time", type=float, default=60.0)
    ap.add_argument("--workers", type=int, default=2)
    ap.add_argument("--instances", nargs="*",
                    default=sorted(glob.glob(os.path.join(HERE, "data", "hides", "*.json"))))
    ap.add_argument("--packingsolver-python", default=None)
    ap.add_argument("--zones", choices=["forbidden", "graded"], default="forbidden")
    ap.add_argument("--repeat", type=int, default=1, help="own runs per instance")
    a = ap.parse_args()
    load = os.getloadavg()
    print(f"time budget {a.time:g} s, {a.workers} workers, zones {a.zones}, "
          f"load average {load[0]:.2f} / {load[1]:.2f} / {load[2]:.2f}")
    print("| instance | engine | hides used / available | placed / copies | dropped "
          "| utilisation of used hides % | per hide % | wall s | valid | load (1 min) |")
    print("|---|---|---|---|---|---|---|---|---|---|")
    for path in a.instances:
        name = os.path.splitext(os.path.basename(path))[0]
        for k in range(max(1, a.repeat)):
            load0 = os.getloadavg()[0]
            rows = [run_own(path, a.time, a.workers, a.zones == "graded")]
            rows[0]["load"] = load0
            if k == 0 and a.packingsolver_python and a.zones == "forbidden":
                own = rows[0]
                objective = "BinPacking" if own["placed"] == own["copies"] else "Knapsack"
                load1 = os.getloadavg()[0]
                rows.append(run_packingsolver(a.packingsolver_python, path, a.time, objective))
                rows[-1]["load"] = load1
            for r in rows:
                _print_row(name, r)
            sys.stdout.flush()


def _print_row(name: str, r: dict) -> None:
    if "error" in r:
        print(f"| {name} | {r['engine']} | error: {r['error']} | | | | | | | |")
        return
    print(f"| {name} | {r['engine']} | {r['hides_used']} / {r['hides']} | "
          f"{r['placed']} / {r['copies']} | {r['dropped']} | {100 * r['utilisation']:.2f} | "
          f"{' '.join(f'{100 * u:.1f}' for u in r['per_hide'])} | {r['wall_s']:.1f} | "
          f"{'yes' if r['valid'] else 'NO'} | {r['load']:.1f} |")


if __name__ == "__main__":
    main()
