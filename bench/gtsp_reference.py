"""Independent reference solvers for the cut-path benchmark (never shipped).

* :func:`noon_bean_reference` -- the GTSP turned into an asymmetric TSP by the
  Noon-Bean transform and solved by LKH-3 (``elkai``, non-commercial licence:
  benchmark only), then the entries re-chosen by our exact DP for LKH's order.
* :func:`pyvrp_reference` -- PyVRP (MIT) with one mutually exclusive client
  group per contour: a single-vehicle routing problem whose solution visits
  exactly one candidate of every contour.
* :func:`lkh_dp_reference` -- LKH-3 on the plain TSP through the currently
  chosen entry points alternated with the DP (a polishing reference: it starts
  from given entries, so it is not independent of them).

All take a :class:`~LeatherCutWorkbench.core.pathplan.instance.EuclidInstance`
with symmetric candidates (start = end, closed contours) whose item 0 is the
single-candidate home; the references ignore precedence (a relaxation: they can
only be shorter than a plan that respects it).  Lengths are in mm.
"""

from __future__ import annotations

import math
import time
from typing import List, Optional, Sequence, Tuple

import numpy as np

from LeatherCutWorkbench.core.pathplan.dp import optimal_entries
from LeatherCutWorkbench.core.pathplan.instance import EuclidInstance
from LeatherCutWorkbench.core.pathplan.nn import nearest_neighbour

try:
    from elkai import _elkai
except ImportError:  # the LKH references are optional
    _elkai = None

try:
    import pyvrp
    from pyvrp.stop import MaxRuntime
except ImportError:  # the PyVRP reference is optional
    pyvrp = None

HAVE_ELKAI = _elkai is not None
HAVE_PYVRP = pyvrp is not None


def _order_of_nodes(inst: EuclidInstance, nodes: Sequence[int]) -> List[int]:
    """Item order of a node sequence (first visit of each item), rotated so
    that the home item 0 comes first."""
    order, seen = [], set()
    for g in nodes:
        k = int(inst.item_of[g])
        if k not in seen:
            seen.add(k)
            order.append(k)
    i0 = order.index(0)
    return order[i0:] + order[:i0]


def _distance_matrix(inst: EuclidInstance, unit_mm: float) -> np.ndarray:
    """Rounded Euclidean distances between all candidates in ``unit_mm`` units
    (int32, built row block by row block to keep the peak memory at one matrix)."""
    S = inst.S
    n = len(S)
    out = np.empty((n, n), dtype=np.int32)
    step = max(1, 4_000_000 // max(n, 1))
    for a in range(0, n, step):
        b = min(n, a + step)
        blk = np.hypot(S[a:b, None, 0] - S[None, :, 0], S[a:b, None, 1] - S[None, :, 1])
        out[a:b] = np.rint(blk / unit_mm)
    return out


def noon_bean_text(inst: EuclidInstance, unit_mm: float = 0.1) -> str:
    """TSPLIB text of the Noon-Bean ATSP of the instance.

    Inside a cluster the candidates form a zero-cost cycle g -> next(g); leaving
    the cluster from g costs the distance from next(g) (where the cluster was
    entered) plus a constant ``big`` charged once per cluster, so an optimal ATSP
    tour runs through each cluster's cycle consecutively and its cost is the
    GTSP tour cost + m * big.  Forbidden arcs get 2 * big + max distance."""
    if not inst.symmetric:
        raise ValueError("the Noon-Bean reference needs symmetric candidates (start = end)")
    n = inst.n
    D = _distance_matrix(inst, unit_mm)
    dmax = int(D.max())
    big = 4 * dmax + 1
    forbidden = 2 * big + dmax
    rows: List[str] = []
    for C in inst.cands:
        c = [int(x) for x in C]
        for i, g in enumerate(c):
            nxt = c[(i + 1) % len(c)]
            row = D[nxt].astype(np.int64) + big
            row[c] = forbidden
            if len(c) > 1:
                row[nxt] = 0
            rows.append((g, " ".join(map(str, row.tolist()))))
    rows.sort(key=lambda r: r[0])
    del D
    head = (f"TYPE : ATSP\nDIMENSION : {n}\nEDGE_WEIGHT_TYPE : EXPLICIT\n"
            f"EDGE_WEIGHT_FORMAT : FULL_MATRIX\nEDGE_WEIGHT_SECTION\n")
    return head + "\n".join(r[1] for r in rows) + "\nEOF\n"


def noon_bean_reference(inst: EuclidInstance, *, runs: int = 1, max_trials: Optional[int] = None,
                        time_limit: Optional[float] = None, seed: int = 1,
                        extra: str = "", unit_mm: float = 0.1) -> Tuple[float, List[int]]:
    """LKH-3 on the Noon-Bean ATSP, then the exact entry DP for LKH's order.
    Returns (idle mm, order).  ``time_limit`` (s) is LKH's own TIME_LIMIT."""
    if _elkai is None:
        raise RuntimeError("elkai is not installed (pip install -r bench/requirements.txt)")
    problem = noon_bean_text(inst, unit_mm)
    params = f"RUNS = {runs}\nSEED = {seed}\nPROBLEM_FILE = :stdin:\n"
    if "MAX_TRIALS" not in extra:
        params += f"MAX_TRIALS = {max_trials or inst.n}\n"
    if time_limit is not None:
        params += f"TIME_LIMIT = {time_limit:g}\n"
    params += extra
    sol = [i - 1 for i in _elkai.solve_problem(params, problem)]
    del problem
    order = _order_of_nodes(inst, sol)
    return optimal_entries(inst, order)[1], order


#: LKH parameters for a strong Noon-Bean run (wider candidate sets, more trials per run)
STRONG_LKH = "MAX_CANDIDATES = 30\nMAX_TRIALS = 1000\n"


def pyvrp_reference(inst: EuclidInstance, *, seconds: float, seed: int = 1,
                    unit_mm: float = 0.01) -> Tuple[float, List[int]]:
    """PyVRP with one required, mutually exclusive client group per contour
    (home = depot), ``seconds`` of wall time; LKH-free and MIT-licensed.  The
    order it returns is re-evaluated with the exact entry DP (never worse than
    PyVRP's own entries).  Returns (idle mm, order)."""
    if pyvrp is None:
        raise RuntimeError("pyvrp is not installed (pip install -r bench/requirements.txt)")
    if len(inst.cands[0]) != 1:
        raise ValueError("item 0 (home) must have exactly one candidate")
    D = _distance_matrix(inst, unit_mm).astype(np.int64)
    locations = [pyvrp.Location(float(x), float(y)) for x, y in inst.S]
    clients, groups, client_node = [], [], []
    for k in range(1, inst.m):
        c = inst.cand_lists[k]
        grouped = len(c) > 1
        first = len(clients)
        for g in c:
            clients.append(pyvrp.Client(location=g, required=not grouped,
                                        group=len(groups) if grouped else None))
            client_node.append(g)
        if grouped:
            groups.append(pyvrp.ClientGroup(list(range(first, first + len(c)))))
    home = int(inst.cands[0][0])
    data = pyvrp.ProblemData(locations, clients, [pyvrp.Depot(home)], [pyvrp.VehicleType(1)],
                             [D], [np.zeros_like(D)], groups)
    del D
    res = pyvrp.solve(data, stop=MaxRuntime(seconds), seed=seed, display=False)
    if not res.best.is_feasible():
        raise RuntimeError("PyVRP returned an infeasible solution")
    nodes = [home] + [client_node[a.idx] for a in res.best.routes()[0] if a.is_client()]
    order = _order_of_nodes(inst, nodes)
    return optimal_entries(inst, order)[1], order


def lkh_tour(points: np.ndarray, seed: int = 1) -> List[int]:
    """LKH-3 (elkai) TSP tour through ``points`` (mm, in 0.01 mm units), from index 0."""
    m = len(points)
    lines = [f"TYPE : TSP\nDIMENSION : {m}\nEDGE_WEIGHT_TYPE : EUC_2D\nNODE_COORD_SECTION"]
    lines += [f"{i + 1} {x * 100:.1f} {y * 100:.1f}" for i, (x, y) in enumerate(points)]
    params = f"RUNS = 1\nMAX_TRIALS = {m}\nSEED = {seed}\nPROBLEM_FILE = :stdin:\n"
    sol = [i - 1 for i in _elkai.solve_problem(params, "\n".join(lines) + "\nEOF\n")]
    i0 = sol.index(0)
    return sol[i0:] + sol[:i0]


def lkh_dp_reference(inst: EuclidInstance, rounds: int = 4,
                     choice: Optional[Sequence[int]] = None) -> float:
    """Alternate LKH (order through the chosen entries) and the exact DP,
    starting from ``choice`` (default: nearest-neighbour entries); idle mm."""
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


def clock(fn):
    """(result, wall s, CPU s) of ``fn()``."""
    w, c = time.perf_counter(), time.process_time()
    out = fn()
    return out, time.perf_counter() - w, time.process_time() - c
