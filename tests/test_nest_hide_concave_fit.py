"""Exact inner-fit regions on hides (``Placer.concave_fit``): a concave part
whose convex hull crosses a concave stretch of the hide outline fits only
with the part's own outline against the outline's pockets; the copy-to-hide
worker uses them, and every layout passes the independent checker."""

import math
import time

from LeatherCutWorkbench.core.model import Container, Part
from LeatherCutWorkbench.core.nesting import ContainerSpec, NestOptions, check_layout
from LeatherCutWorkbench.core.nesting.engine import _to_layout, prepare
from LeatherCutWorkbench.core.nesting.search import Budget, run_search

from nest_shapes import poly_contour

#: a 100 x 100 mm hide with a 20 mm wide slot 70 mm deep cut in from its top edge
HIDE_U = [(0, 0), (100, 0), (100, 100), (60, 100), (60, 30), (40, 30), (40, 100), (0, 100)]
#: a 96 x 96 mm part with a 24 mm wide, 72 mm deep slot: it fits the hide only
#: astride the hide's slot (2 mm to spare on each side), its convex hull nowhere
PART_U = [(0, 0), (96, 0), (96, 96), (60, 96), (60, 24), (36, 24), (36, 96), (0, 96)]


def _instance(n_hides: int):
    hides = [Container(id=f"u{k}", kind="hide", outline=list(HIDE_U), base_grade=1)
             for k in range(n_hides)]
    parts = [Part(id="u", outer=poly_contour("u/o", PART_U), quantity=1, rotations=[0.0],
                  grade=1)]
    opts = NestOptions(container=ContainerSpec.hide(*hides), time_budget=10, workers=1,
                       rotations_override=[0.0], seed=1)
    return parts, hides, opts, prepare(parts, opts)


def test_a_concave_part_fits_a_concave_hide_only_with_the_exact_region():
    parts, hides, opts, (types, variants, problem, copies, _h, scale) = _instance(1)
    seq = [(t, None) for t in copies]
    hull = problem.placer()
    tr = hull.place(seq, abortable=False)
    assert tr.unplaced == [0]                 # its convex hull overlaps the slot everywhere
    exact = problem.placer()
    exact.concave_fit = True
    tr = exact.place(seq, abortable=False)
    assert tr.unplaced == []
    (_si, b, vi, tx, ty), = tr.placements
    # astride the slot: the part's origin within the 4 x 6 mm window it has
    assert abs(tx / scale - 2.0) <= 2.0 + 1e-6 and abs(ty / scale - 2.0) <= 4.0 + 1e-6
    lay = _to_layout(parts, types, variants, seq, tr.placements, opts, scale, hides)
    assert check_layout(parts, lay, rotations_override=[0.0]) == []
    assert lay.metrics["hides"] == 1 and lay.metrics["unplaced_count"] == 0
    assert math.isclose(lay.metrics["utilisation"],
                        (96 * 96 - 24 * 72) / (100 * 100 - 20 * 70), rel_tol=1e-6)


def test_the_copy_to_hide_worker_places_what_the_order_search_cannot():
    parts, hides, opts, (types, variants, problem, copies, _h, scale) = _instance(2)
    got = {}
    for worker in (0, 1):
        budget = Budget(time.monotonic() + 30.0, max_evaluations=6)
        cost, seq, placements, _evals = run_search(problem, copies, 1, worker, budget)
        got[worker] = (cost, seq, placements)
    assert got[0][0][0] > 0                   # the order search: hull regions, left out
    cost, seq, placements = got[1]
    assert cost[0] == 0 and cost[1] == 1      # the copy-to-hide worker: placed on one hide
    lay = _to_layout(parts, types, variants, seq, placements, opts, scale, hides)
    assert check_layout(parts, lay, rotations_override=[0.0]) == []
    assert lay.metrics["placed_count"] == 1
