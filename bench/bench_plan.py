"""Cut-path planning benchmark: idle travel and time of the planner's methods.

Run:  /work/main/.venv/bin/python bench/bench_plan.py [--quick] [--sizes 100,1000] [--time 30]

Prints Markdown tables:

1. the 62-part synthetic leather job (1000 x 1000 mm hide, 9 parts with a
   hole, shuffled drawing order; tests/plan_shapes.leather_job): drawing
   order, NN, ACO, GA, and the certified lower bound;
2. scaling 100 -> 5,000 contours with ~20 entry candidates each: NN, GA (time
   budget per size), and a strong reference where feasible.

Reference ("LKH+DP"): LKH-3 through the ``elkai`` package (non-commercial
licence: benchmark-only, ``pip install -r bench/requirements.txt``) solves the
TSP through the currently chosen entry points; the exact entry DP then
re-chooses the entries for LKH's order; repeated until no gain (max 4
rounds), starting from nearest-neighbour entries.  The Noon-Bean GTSP->ATSP
transform would need a full 20,000 x 20,000 text matrix for 1,000 contours x
20 candidates, which elkai cannot take; on the small hide job it is run as
well ("LKH Noon-Bean + DP").  Times are wall and CPU (time.process_time)
seconds: the machine is shared, CPU seconds are the comparable figure.
"""

from __future__ import annotations

import argparse
import datetime
import math
import os
import sys
import time

import numpy as np

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(HERE)
sys.path.insert(0, ROOT)
sys.path.insert(0, os.path.join(ROOT, "tests"))

from LeatherCutWorkbench.core.pathplan import PlanOptions, plan  # noqa: E402
from LeatherCutWorkbench.core.pathplan.bounds import lower_bound  # noqa: E402
from LeatherCutWorkbench.core.pathplan.dp import optimal_entries  # noqa: E402
from LeatherCutWorkbench.core.pathplan.ga import run_ga  # noqa: E402
from LeatherCutWorkbench.core.pathplan.items import build_items  # noqa: E402
from LeatherCutWorkbench.core.pathplan.nn import nearest_neighbour  # noqa: E402
from LeatherCutWorkbench.core.pathplan.planner import build_instance  # noqa: E402
from plan_shapes import leather_job  # noqa: E402

try:
    from elkai import _elkai
except ImportError:  # reference is optional
    _elkai = None


def instance_for(parts, spacing: float):
    items, preds, _ = build_items(parts, [], entry_spacing=spacing, max_candidates=64,
                                  cut_open_chains=False, common_edge_tol=0.05)
    return build_instance(items, preds, (0.0, 0.0))


def lkh_tour(points: np.ndarray, seed: int = 1) -> list:
    """LKH-3 (elkai) TSP tour through ``points`` (mm, scaled x100 to integers)."""
    m = len(points)
    lines = [f"TYPE : TSP\nDIMENSION : {m}\nEDGE_WEIGHT_TYPE : EUC_2D\nNODE_COORD_SECTION"]
    lines += [f"{i + 1} {x * 100:.1f} {y * 100:.1f}" for i, (x, y) in enumerate(points)]
    params = f"RUNS = 1\nMAX_TRIALS = {m}\nSEED = {seed}\nPROBLEM_FILE = :stdin:\n"
    sol = [i - 1 for i in _elkai.solve_problem(params, "\n".join(lines) + "\nEOF\n")]
    i0 = sol.index(0)
    return sol[i0:] + sol[:i0]


def lkh_dp_reference(inst, rounds: int = 4, choice=None):
    """Alternate LKH (order through the chosen entries) and the exact DP,
    starting from ``choice`` (default: nearest-neighbour entries)."""
    if choice is None:
        _, choice = nearest_neighbour(inst)
    best = math.inf
    for _ in range(rounds):
        pts = np.array([inst.S[choice[k]] for k in range(inst.m)])
        order = lkh_tour(pts)
        choice2, cost = optimal_entries(inst, order)
        if cost >= best - 1e-6:
            break
        best, choice = cost, choice2
    return best


NB_RUNS = 1
NB_EXTRA = ""


def noon_bean_reference(inst) -> float:
    """LKH-3 on the Noon-Bean ATSP of the GTSP (symmetric candidates), then DP."""
    n = inst.n
    pts = inst.S
    D = np.hypot(pts[:, None, 0] - pts[None, :, 0], pts[:, None, 1] - pts[None, :, 1])
    D10 = np.round(D * 10.0)                       # 0.1 mm units
    big = 4.0 * D10.max() + 1.0                    # charged once per cluster exit
    A = np.full((n, n), 2.0 * big + D10.max())     # forbidden arcs
    for C in inst.cands:
        c = [int(x) for x in C]
        others = np.ones(n, dtype=bool)
        others[c] = False
        for i, g in enumerate(c):
            nxt = c[(i + 1) % len(c)]
            # entered at nxt, the zero-cost cycle ends at g: leaving from g is
            # really leaving from nxt
            A[g, others] = D10[nxt, others] + big
            if len(c) > 1:
                A[g, nxt] = 0.0
    A = A.astype(np.int64)
    lines = [f"TYPE : ATSP\nDIMENSION : {n}\nEDGE_WEIGHT_TYPE : EXPLICIT\n"
             f"EDGE_WEIGHT_FORMAT : FULL_MATRIX\nEDGE_WEIGHT_SECTION"]
    lines += [" ".join(map(str, row)) for row in A.tolist()]
    params = f"RUNS = {NB_RUNS}\nMAX_TRIALS = {n}\nSEED = 1\nPROBLEM_FILE = :stdin:\n{NB_EXTRA}"
    sol = [i - 1 for i in _elkai.solve_problem(params, "\n".join(lines) + "\nEOF\n")]
    order, seen = [], set()
    for g in sol:
        k = int(inst.item_of[g])
        if k not in seen:
            seen.add(k)
            order.append(k)
    i0 = order.index(0)
    order = order[i0:] + order[:i0]
    return optimal_entries(inst, order)[1]


def fst_instance(n: int, seed: int):
    """GTSPLIB-style instance: n uniform points in 1000 x 1000, ceil(n/5)
    clusters by the Fischetti-Salazar-Toth rule (farthest-point centres,
    nearest-centre assignment)."""
    from LeatherCutWorkbench.core.pathplan.instance import EuclidInstance
    rng = np.random.default_rng(seed)
    pts = rng.uniform(0, 1000, (n, 2))
    m = math.ceil(n / 5)
    centres = [0]
    d = np.hypot(*(pts - pts[0]).T)
    for _ in range(m - 1):
        j = int(d.argmax())
        centres.append(j)
        d = np.minimum(d, np.hypot(*(pts - pts[j]).T))
    C = pts[centres]
    lab = np.argmin(np.hypot(pts[:, None, 0] - C[None, :, 0], pts[:, None, 1] - C[None, :, 1]), axis=1)
    order = np.concatenate([np.flatnonzero(lab == k) for k in range(m)])
    P = pts[order]
    clusters, off = [], 0
    for k in range(m):
        sz = int((lab == k).sum())
        clusters.append(list(range(off, off + sz)))
        off += sz
    return P, clusters, EuclidInstance(clusters, P)


def fst_table(sizes, time_limit: float, with_ref: bool) -> str:
    from LeatherCutWorkbench.core.pathplan import solve_gtsp
    global NB_RUNS
    rows = ["| nodes | clusters | solve_gtsp (GA) | GA wall s | GA CPU s | LKH-3 Noon-Bean + DP, RUNS=5 | LKH CPU s | GA vs LKH |",
            "|---:|---:|---:|---:|---:|---:|---:|---:|"]
    for n in sizes:
        P, clusters, inst = fst_instance(n, 1)
        D = np.hypot(P[:, None, 0] - P[None, :, 0], P[:, None, 1] - P[None, :, 1])
        tour, w, c = clock(lambda: solve_gtsp(D, clusters, time_limit=time_limit, seed=1))
        ga = float(sum(D[a, b] for a, b in zip(tour, tour[1:] + tour[:1])))
        ref_s, rc_s, gap = "—", "—", "—"
        if with_ref and _elkai is not None:
            NB_RUNS = 5
            ref, _, rc = clock(lambda: noon_bean_reference(inst))
            NB_RUNS = 1
            ref_s, rc_s, gap = f"{ref:.1f}", f"{rc:.1f}", f"{100 * (ga / ref - 1):+.2f} %"
        rows.append(f"| {n} | {len(clusters)} | {ga:.1f} | {w:.1f} | {c:.1f} | {ref_s} | {rc_s} | {gap} |")
        print(rows[-1], file=sys.stderr, flush=True)
    return "\n".join(rows)


def clock(fn):
    w, c = time.perf_counter(), time.process_time()
    out = fn()
    return out, time.perf_counter() - w, time.process_time() - c


def hide_table(time_limit: float, with_ref: bool) -> str:
    parts = leather_job(seed=1)
    rows = ["| plan | idle travel mm | vs drawing order | vs NN | wall s | CPU s |",
            "|---|---:|---:|---:|---:|---:|"]
    res = {}
    for meth in ("nn", "aco", "ga", "ga10"):
        tl = 10.0 if meth == "ga10" else time_limit
        p, w, c = clock(lambda: plan(parts, [], PlanOptions(method=meth[:2] if meth != "aco" else meth,
                                                            time_limit=tl, seed=1)))
        res[meth] = (p, w, c)
    draw = res["ga"][0].metrics["drawing_order_idle_mm"]
    nn = res["nn"][0].metrics["idle_mm"]
    rows.append(f"| drawing order (first vertex) | {draw:.0f} | 0 % | | | |")
    for meth, label in (("nn", "nearest neighbour"), ("aco", "ACO (MMAS)"), ("ga", "GA (default)"),
                        ("ga10", "GA, 10 s budget")):
        p, w, c = res[meth]
        idle = p.metrics["idle_mm"]
        rows.append(f"| {label} | {idle:.0f} | {100 * (idle / draw - 1):+.1f} % | "
                    f"{100 * (idle / nn - 1):+.1f} % | {w:.2f} | {c:.2f} |")
    inst = instance_for(parts, 20.0)
    if with_ref and _elkai is not None:
        global NB_RUNS
        NB_RUNS = 3
        (ref, w, c) = clock(lambda: noon_bean_reference(inst))
        NB_RUNS = 1
        rows.append(f"| LKH-3 Noon-Bean + DP, RUNS=3 (elkai, reference) | {ref:.0f} | "
                    f"{100 * (ref / draw - 1):+.1f} % | {100 * (ref / nn - 1):+.1f} % | {w:.1f} | {c:.1f} |")
        (ref2, w, c) = clock(lambda: lkh_dp_reference(inst))
        rows.append(f"| LKH-3 + DP alternation (reference) | {ref2:.0f} | "
                    f"{100 * (ref2 / draw - 1):+.1f} % | {100 * (ref2 / nn - 1):+.1f} % | {w:.1f} | {c:.1f} |")
    lb = res["ga"][0].metrics["lower_bound_mm"]
    rows.append(f"| certified lower bound | {lb:.0f} | | | | |")
    m = res["ga"][0].metrics
    head = (f"62 parts, {m['items']} contours, {m['entry_candidates']} entry candidates "
            f"(every 20 mm + vertices), home (0, 0); GA/ACO time limit {time_limit:g} s "
            f"(stop earlier when converged).")
    return head + "\n\n" + "\n".join(rows)


def scaling_table(sizes, time_for, with_ref: bool, ref_max: int) -> str:
    rows = ["| contours | candidates | NN idle | GA idle | GA vs NN | reference: best (from NN / from GA entries) | GA vs reference "
            "| GA wall s | GA CPU s | GA generations | ref CPU s | lower bound |",
            "|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|"]
    for m in sizes:
        size = 1000.0 * math.sqrt(m / 62.0)
        parts = leather_job(seed=m, n_parts=m, n_holes=0, size=size)
        inst = instance_for(parts, 25.0)
        tl = time_for(m)
        order, choice = nearest_neighbour(inst)
        nn = inst.tour_cost(order, choice)
        r, w, c = clock(lambda: run_ga(inst, time_limit=tl, seed=1))
        ref_s, ref_c = "—", "—"
        gap = "—"
        if with_ref and _elkai is not None and m <= ref_max:
            ref1, _, rc1 = clock(lambda: lkh_dp_reference(inst))
            ref2, _, rc2 = clock(lambda: lkh_dp_reference(inst, choice=r.choice))
            ref = min(ref1, ref2)
            ref_s, ref_c = f"{ref:.0f} ({ref1:.0f} / {ref2:.0f})", f"{rc1 + rc2:.1f}"
            gap = f"{100 * (r.cost / ref - 1):+.2f} %"
        lb, _ = lower_bound(inst, r.cost, time_budget=5.0, max_items_hk=1200)
        rows.append(f"| {m} | {inst.n - 1} | {nn:.0f} | {r.cost:.0f} | {100 * (r.cost / nn - 1):+.1f} % | "
                    f"{ref_s} | {gap} | {w:.1f} | {c:.1f} | {r.iterations} | {ref_c} | {lb:.0f} |")
        print(rows[-1], file=sys.stderr, flush=True)
    return "\n".join(rows)


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--quick", action="store_true", help="small sizes, short budgets")
    ap.add_argument("--sizes", default="100,200,500,1000,2000,5000")
    ap.add_argument("--time", type=float, default=25.0, help="GA time limit (s) for 1,000 contours")
    ap.add_argument("--hide-time", type=float, default=2.0, help="GA/ACO time limit on the hide job")
    ap.add_argument("--no-ref", action="store_true", help="skip the LKH reference")
    ap.add_argument("--ref-max", type=int, default=2000, help="largest size given a reference")
    ap.add_argument("--skip-hide", action="store_true")
    ap.add_argument("--fst", default="200,400,1000", help="GTSPLIB-style node counts ('' = skip)")
    ap.add_argument("--fst-time", type=float, default=10.0)
    a = ap.parse_args()
    sizes = [int(s) for s in a.sizes.split(",")]
    if a.quick:
        sizes = [s for s in sizes if s <= 500]

    def time_for(m: int) -> float:
        return max(2.0, a.time * m / 1000.0) if m <= 1000 else a.time * m / 1000.0

    print(f"# bench_plan.py — {datetime.datetime.utcnow():%Y-%m-%d %H:%M} UTC, "
          f"elkai {'present' if _elkai else 'absent (no reference)'}\n")
    if not a.skip_hide:
        print("## 62-part leather job\n")
        print(hide_table(a.hide_time, not a.no_ref))
        print()
    if a.fst:
        print("## GTSPLIB-style instances (solve_gtsp)\n")
        print(fst_table([int(v) for v in a.fst.split(",")], a.fst_time, not a.no_ref))
        print()
    print("## Scaling (GA time limit = %g s x contours / 1000, min 2 s)\n" % a.time)
    print(scaling_table(sizes, time_for, not a.no_ref, a.ref_max))


if __name__ == "__main__":
    main()
