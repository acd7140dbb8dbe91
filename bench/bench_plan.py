"""Cut-path planning benchmark: idle travel and time of the planner's methods.

Run:  /work/main/.venv/bin/python bench/bench_plan.py [--quick] [--sizes 100,1000] [--time 30]

Prints Markdown tables:

1. the 62-part synthetic leather job (1000 x 1000 mm hide, 9 parts with a
   hole, shuffled drawing order; tests/plan_shapes.leather_job): drawing
   order, NN, ACO, GA, and the certified lower bound;
2. GTSPLIB-style random instances through ``solve_gtsp``;
3. scaling 100 -> 5,000 contours with ~20 entry candidates each: NN, GA (time
   budget per size) and the references below where feasible.

References (bench/gtsp_reference.py; ``pip install -r bench/requirements.txt``):

* LKH-3 Noon-Bean + DP: the GTSP as an asymmetric TSP (Noon-Bean transform)
  solved by LKH-3 through ``elkai`` (non-commercial licence: benchmark only),
  entries re-chosen by the exact DP.  Independent of our search; run up to
  ``--nb-max`` contours (1,000 x ~18 candidates = a 17,777-node explicit matrix,
  ~1.9 GB of TSPLIB text, in 1 mm units: elkai crashes on text over 2 GiB).
* LKH-3 strong: the same with MAX_CANDIDATES = 30, MAX_TRIALS = 1000 and
  several runs (``--strong-max``, ``--strong-runs``): the setting that reached
  the proven optima of GTSPLIB instances in the team's measurements.
* PyVRP client groups (MIT): one mutually exclusive group per contour.
* LKH + DP polishing: LKH-3 on the TSP through the chosen entries alternated
  with the DP, started from NN entries and from the GA's entries (not
  independent: it measures what LKH still finds in the GA's plan).

The references ignore precedence (the scaling jobs have none).  Times are wall
and CPU (time.process_time) seconds: CPU seconds are the comparable figure on
a shared machine.
"""

from __future__ import annotations

import argparse
import datetime
import math
import os
import resource
import sys

import numpy as np

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(HERE)
sys.path.insert(0, ROOT)
sys.path.insert(0, os.path.join(ROOT, "tests"))

from LeatherCutWorkbench.core.pathplan import PlanOptions, plan  # noqa: E402
from LeatherCutWorkbench.core.pathplan.bounds import lower_bound  # noqa: E402
from LeatherCutWorkbench.core.pathplan.ga import run_ga  # noqa: E402
from LeatherCutWorkbench.core.pathplan.items import build_items  # noqa: E402
from LeatherCutWorkbench.core.pathplan.nn import nearest_neighbour  # noqa: E402
from LeatherCutWorkbench.core.pathplan.planner import build_instance  # noqa: E402
from plan_shapes import leather_job  # noqa: E402

from gtsp_reference import (HAVE_ELKAI, HAVE_PYVRP, STRONG_LKH, clock,  # noqa: E402
                            lkh_dp_reference, noon_bean_reference, pyvrp_reference)


def instance_for(parts, spacing: float):
    items, preds, _ = build_items(parts, [], entry_spacing=spacing, max_candidates=64,
                                  cut_open_chains=False, common_edge_tol=0.05)
    return build_instance(items, preds, (0.0, 0.0))


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
    rows = ["| nodes | clusters | solve_gtsp (GA) | GA wall s | GA CPU s | LKH-3 Noon-Bean + DP, RUNS=5 | LKH CPU s | GA vs LKH |",
            "|---:|---:|---:|---:|---:|---:|---:|---:|"]
    for n in sizes:
        P, clusters, inst = fst_instance(n, 1)
        D = np.hypot(P[:, None, 0] - P[None, :, 0], P[:, None, 1] - P[None, :, 1])
        tour, w, c = clock(lambda: solve_gtsp(D, clusters, time_limit=time_limit, seed=1))
        ga = float(sum(D[a, b] for a, b in zip(tour, tour[1:] + tour[:1])))
        ref_s, rc_s, gap = "—", "—", "—"
        if with_ref and HAVE_ELKAI:
            (ref, _), _, rc = clock(lambda: noon_bean_reference(inst, runs=5))
            ref_s, rc_s, gap = f"{ref:.1f}", f"{rc:.1f}", f"{100 * (ga / ref - 1):+.2f} %"
        rows.append(f"| {n} | {len(clusters)} | {ga:.1f} | {w:.1f} | {c:.1f} | {ref_s} | {rc_s} | {gap} |")
        print(rows[-1], file=sys.stderr, flush=True)
    return "\n".join(rows)


def hide_table(time_limit: float, with_ref: bool, generations=()) -> str:
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
    for g in generations:
        p, w, c = clock(lambda: plan(parts, [], PlanOptions(method="ga", time_limit=3600, seed=1,
                                                            max_iterations=g)))
        idle = p.metrics["idle_mm"]
        rows.append(f"| GA, {g} generations (any machine) | {idle:.0f} | {100 * (idle / draw - 1):+.1f} % | "
                    f"{100 * (idle / nn - 1):+.1f} % | {w:.2f} | {c:.2f} |")
    inst = instance_for(parts, 20.0)
    if with_ref and HAVE_ELKAI:
        (ref, _), w, c = clock(lambda: noon_bean_reference(inst, runs=3))
        rows.append(f"| LKH-3 Noon-Bean + DP, RUNS=3 (elkai, reference) | {ref:.0f} | "
                    f"{100 * (ref / draw - 1):+.1f} % | {100 * (ref / nn - 1):+.1f} % | {w:.1f} | {c:.1f} |")
        if HAVE_PYVRP:
            (ref3, _), w, c = clock(lambda: pyvrp_reference(inst, seconds=60.0))
            rows.append(f"| PyVRP client groups, 60 s (reference) | {ref3:.0f} | "
                        f"{100 * (ref3 / draw - 1):+.1f} % | {100 * (ref3 / nn - 1):+.1f} % | {w:.1f} | {c:.1f} |")
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


def noon_bean_unit(inst) -> float:
    """Matrix unit (mm) for the Noon-Bean text: 0.1 mm while the TSPLIB text
    stays below elkai's 2 GiB string limit (it crashes above), else 1 mm (the
    DP re-evaluates LKH's order with exact distances either way)."""
    return 0.1 if inst.n ** 2 * 7 < 1.9e9 else 1.0


def scaling_table(sizes, time_for, a) -> str:
    """GA against NN, the independent references (LKH-3 Noon-Bean, PyVRP) and
    LKH + DP polishing, per size; ``a`` holds the command-line limits."""
    rows = ["| contours | candidates | NN idle | GA idle | GA vs NN | GA wall s | GA CPU s | GA generations "
            "| GA, 20x time | GA vs 20x | peak RSS MB "
            "| LKH-3 Noon–Bean + DP | its CPU s | GA vs LKH-3 | LKH-3 strong | its CPU s | GA vs strong "
            "| PyVRP groups | GA vs PyVRP "
            "| LKH + DP polishing | GA vs polishing | lower bound |",
            "|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:"
            "|---:|---:|---:|"]
    for m in sizes:
        size = 1000.0 * math.sqrt(m / 62.0)
        parts = leather_job(seed=m, n_parts=m, n_holes=0, size=size)
        inst = instance_for(parts, 25.0)
        tl = time_for(m)
        order, choice = nearest_neighbour(inst)
        nn = inst.tour_cost(order, choice)
        r, w, c = clock(lambda: run_ga(inst, time_limit=tl, seed=1))
        ga = r.cost

        def gap(ref):
            return f"{100 * (ga / ref - 1):+.2f} %"
        long_s = long_gap = "—"
        if m in a.long_sizes:
            r20 = run_ga(inst, time_limit=20 * tl, seed=1)
            long_s, long_gap = f"{r20.cost:.0f} ({r20.stopped_by})", gap(r20.cost)
        rss = resource.getrusage(resource.RUSAGE_SELF).ru_maxrss / 1024.0
        nb = nb_c = nb_gap = st = st_c = st_gap = pv = pv_gap = pol = pol_gap = "—"
        if HAVE_ELKAI and m <= a.nb_max:
            period = f"INITIAL_PERIOD = {a.nb_period}\n" if a.nb_period else ""
            (ref, _), _, rc = clock(lambda: noon_bean_reference(
                inst, runs=1, time_limit=a.nb_time, unit_mm=noon_bean_unit(inst), extra=period))
            nb, nb_c, nb_gap = f"{ref:.0f}", f"{rc:.0f}", gap(ref)
        if HAVE_ELKAI and m <= a.strong_max:
            (ref, _), _, rc = clock(lambda: noon_bean_reference(
                inst, runs=a.strong_runs, extra=STRONG_LKH, unit_mm=noon_bean_unit(inst)))
            st, st_c, st_gap = f"{ref:.0f}", f"{rc:.0f}", gap(ref)
        if HAVE_PYVRP and m <= a.pyvrp_max:
            ref, _ = pyvrp_reference(inst, seconds=a.pyvrp_time)
            pv, pv_gap = f"{ref:.0f}", gap(ref)
        if HAVE_ELKAI and m <= a.ref_max:
            ref = min(lkh_dp_reference(inst), lkh_dp_reference(inst, choice=r.choice))
            pol, pol_gap = f"{ref:.0f}", gap(ref)
        lb, _ = lower_bound(inst, ga, time_budget=5.0, max_items_hk=1200)
        rows.append(f"| {m} | {inst.n - 1} | {nn:.0f} | {ga:.0f} | {100 * (ga / nn - 1):+.1f} % | "
                    f"{w:.1f} | {c:.1f} | {r.iterations} ({r.stopped_by}) | {long_s} | {long_gap} | "
                    f"{rss:.0f} | {nb} | {nb_c} | {nb_gap} | "
                    f"{st} | {st_c} | {st_gap} | "
                    f"{pv} | {pv_gap} | {pol} | {pol_gap} | {lb:.0f} |")
        print(rows[-1], file=sys.stderr, flush=True)
    return "\n".join(rows)


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--quick", action="store_true", help="small sizes, short budgets")
    ap.add_argument("--sizes", default="100,200,500,1000,2000,5000")
    ap.add_argument("--time", type=float, default=25.0, help="GA time limit (s) for 1,000 contours")
    ap.add_argument("--hide-time", type=float, default=2.0, help="GA/ACO time limit on the hide job")
    ap.add_argument("--no-ref", action="store_true", help="skip every reference solver")
    ap.add_argument("--ref-max", type=int, default=2000, help="largest size given LKH + DP polishing")
    ap.add_argument("--nb-max", type=int, default=1000, help="largest size given LKH-3 Noon-Bean")
    ap.add_argument("--nb-time", type=float, default=1800.0, help="LKH-3 TIME_LIMIT (s) at scale")
    ap.add_argument("--nb-period", type=int, default=0,
                    help="LKH-3 INITIAL_PERIOD of the Noon-Bean ascent (default: LKH's, n/2)")
    ap.add_argument("--strong-max", type=int, default=200,
                    help="largest size given LKH-3 with strong parameters (MAX_CANDIDATES 30)")
    ap.add_argument("--strong-runs", type=int, default=3, help="LKH-3 runs of the strong reference")
    ap.add_argument("--pyvrp-max", type=int, default=500, help="largest size given PyVRP")
    ap.add_argument("--pyvrp-time", type=float, default=60.0, help="PyVRP wall seconds")
    ap.add_argument("--skip-hide", action="store_true")
    ap.add_argument("--hide-iterations", default="",
                    help="also plan the hide job with these GA generation budgets, e.g. 25,50,100")
    ap.add_argument("--long-sizes", default="1000,5000",
                    help="sizes also given 20x the GA time (the 'same search, more time' reference)")
    ap.add_argument("--fst", default="200,400,1000", help="GTSPLIB-style node counts ('' = skip)")
    ap.add_argument("--fst-time", type=float, default=10.0)
    a = ap.parse_args()
    if a.no_ref:
        a.ref_max = a.nb_max = a.strong_max = a.pyvrp_max = 0
    sizes = [int(s) for s in a.sizes.split(",") if s]
    a.long_sizes = [int(s) for s in a.long_sizes.split(",") if s]
    if a.quick:
        sizes = [s for s in sizes if s <= 500]

    def time_for(m: int) -> float:
        return max(2.0, a.time * m / 1000.0) if m <= 1000 else a.time * m / 1000.0

    print(f"# bench_plan.py — {datetime.datetime.utcnow():%Y-%m-%d %H:%M} UTC, "
          f"elkai {'present' if HAVE_ELKAI else 'absent'}, pyvrp {'present' if HAVE_PYVRP else 'absent'}, "
          f"load average {os.getloadavg()[0]:.1f}\n")
    if not a.skip_hide:
        print("## 62-part leather job\n")
        print(hide_table(a.hide_time, not a.no_ref,
                         [int(g) for g in a.hide_iterations.split(",") if g]))
        print()
    if a.fst:
        print("## GTSPLIB-style instances (solve_gtsp)\n")
        print(fst_table([int(v) for v in a.fst.split(",")], a.fst_time, not a.no_ref))
        print()
    if sizes:
        print("## Scaling (GA time limit = %g s x contours / 1000, min 2 s)\n" % a.time)
        print(scaling_table(sizes, time_for, a))


if __name__ == "__main__":
    main()
