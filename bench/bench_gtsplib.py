"""GTSPLIB benchmark: ``solve_gtsp`` against the proven optima.

Run:  .venv/bin/python bench/bench_gtsplib.py [--times 1,10,30] [--iterations 300]
                                              [--refs] [--instances 39rat195,...]

Instances are built from the TSPLIB coordinates in bench/data/tsplib/ by the
Fischetti-Salazar-Toth clustering (bench/gtsplib.py); instances whose
coordinate file is missing are listed as such.  Each instance is solved
with every wall-time budget of ``--times`` (seed 1) and with a fixed
generation budget ``--iterations`` (reproducible on any machine, whatever the
load).  ``--refs`` adds LKH-3 (elkai, Noon-Bean transform + our exact DP on
its order, RUNS = 1) and PyVRP (client groups, 10 s) on the same instances,
benchmark only.  Prints a Markdown table; gaps are against the proven optima.
"""

from __future__ import annotations

import argparse
import datetime
import os
import sys
import time

import numpy as np

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, os.path.dirname(HERE))
sys.path.insert(0, HERE)

import gtsplib  # noqa: E402
from LeatherCutWorkbench.core.pathplan import solve_gtsp  # noqa: E402
from LeatherCutWorkbench.core.pathplan.gtsp import gtsp_instance  # noqa: E402
from LeatherCutWorkbench.core.pathplan.instance import EuclidInstance, MatrixInstance  # noqa: E402
from LeatherCutWorkbench.core.pathplan.memetic import run_memetic  # noqa: E402


def matrix_instance(D, clusters):
    """The instance solve_gtsp builds (smallest cluster first as the anchor)."""
    return gtsp_instance(D, clusters)[0]


def references(name: str, D, clusters):
    """(LKH-3 Noon-Bean + DP, its CPU s, PyVRP 10 s) tour lengths or None."""
    from gtsp_reference import HAVE_ELKAI, HAVE_PYVRP, noon_bean_reference, pyvrp_reference
    P = gtsplib.read_tsp(gtsplib.OPTIMA[name][0])
    # an EuclidInstance on the nodes with the home = the smallest cluster's first node;
    # the references price moves with these coordinates and the DP re-evaluates exactly
    minst, node_of = gtsp_instance(D, clusters)
    nodes, new = node_of.tolist(), minst.cand_lists
    inst = EuclidInstance(new, P[nodes])
    lkh = pv = lkh_cpu = None
    if HAVE_ELKAI:
        c = time.process_time()
        _, o = noon_bean_reference(inst, runs=1, unit_mm=1.0)
        lkh_cpu = time.process_time() - c
        lkh = _rounded(D, nodes, new, o)
    if HAVE_PYVRP and len(new[0]) == 1:
        _, o = pyvrp_reference(inst, seconds=10.0, unit_mm=1.0)
        pv = _rounded(D, nodes, new, o)
    return lkh, lkh_cpu, pv


def _rounded(D, nodes, clusters, order):
    """Exact TSPLIB length of the best entries for an item order (DP on D)."""
    from LeatherCutWorkbench.core.pathplan.dp import optimal_entries
    inst = MatrixInstance(D, clusters, start_node=np.array(nodes), end_node=np.array(nodes))
    return optimal_entries(inst, order)[1]


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--times", default="1,10,30", help="wall-time budgets (s)")
    ap.add_argument("--iterations", type=int, default=300, help="fixed generation budget (0 = skip)")
    ap.add_argument("--instances", default=",".join(gtsplib.OPTIMA))
    ap.add_argument("--refs", action="store_true", help="LKH-3 (elkai) and PyVRP side by side")
    a = ap.parse_args()
    times = [float(t) for t in a.times.split(",") if t]
    names = a.instances.split(",")
    load = os.getloadavg()
    print(f"# bench_gtsplib.py -- {datetime.datetime.utcnow():%Y-%m-%d %H:%M} UTC, "
          f"load average {load[0]:.1f} / {load[1]:.1f} / {load[2]:.1f}, {os.cpu_count()} cores\n")
    head = ["instance", "optimum"] + [f"{t:g} s (gap, CPU s)" for t in times]
    if a.iterations:
        head.append(f"{a.iterations} generations (gap, CPU s)")
    if a.refs:
        head += ["LKH-3 Noon-Bean + DP (gap, CPU s)", "PyVRP groups 10 s (gap)"]
    print("| " + " | ".join(head) + " |")
    print("|---|---:|" + "---:|" * (len(head) - 2))
    gaps = {t: [] for t in times}
    gaps["it"] = []
    for name in names:
        if name not in gtsplib.available():
            print(f"| {name} | {gtsplib.OPTIMA[name][1]} | " + " | ".join(
                ["coordinates not available"] + [""] * (len(head) - 3)) + " |", flush=True)
            continue
        D, clusters, opt = gtsplib.instance(name)
        cells = [name, str(opt)]
        for t in times:
            c = time.process_time()
            tour = solve_gtsp(D, clusters, time_limit=t, seed=1)
            cpu = time.process_time() - c
            L = gtsplib.tour_length(D, tour)
            gaps[t].append(L / opt - 1)
            cells.append(f"{L:.0f} ({100 * (L / opt - 1):+.2f} %, {cpu:.1f})")
        if a.iterations:
            inst = matrix_instance(D, clusters)
            c = time.process_time()
            r = run_memetic(inst, time_limit=3600, seed=1, max_iterations=a.iterations)
            cpu = time.process_time() - c
            gaps["it"].append(r.cost / opt - 1)
            cells.append(f"{r.cost:.0f} ({100 * (r.cost / opt - 1):+.2f} %, {cpu:.1f}, {r.stopped_by})")
        if a.refs:
            lkh, lkh_cpu, pv = references(name, D, clusters)
            cells.append("—" if lkh is None else f"{lkh:.0f} ({100 * (lkh / opt - 1):+.2f} %, {lkh_cpu:.1f})")
            cells.append("—" if pv is None else f"{pv:.0f} ({100 * (pv / opt - 1):+.2f} %)")
        print("| " + " | ".join(cells) + " |", flush=True)
    summ = ["**mean / worst gap**", ""]
    for t in times:
        g = gaps[t]
        summ.append(f"{100 * np.mean(g):+.2f} % / {100 * max(g):+.2f} %" if g else "")
    if a.iterations:
        g = gaps["it"]
        summ.append(f"{100 * np.mean(g):+.2f} % / {100 * max(g):+.2f} %" if g else "")
    if a.refs:
        summ += ["", ""]
    print("| " + " | ".join(summ) + " |")
    load = os.getloadavg()
    print(f"\nload average at the end {load[0]:.1f} / {load[1]:.1f} / {load[2]:.1f}")


if __name__ == "__main__":
    main()
