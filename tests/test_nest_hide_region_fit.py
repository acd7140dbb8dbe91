"""Inner-fit regions of graded part regions on hides (blf.Placer._region_fit):
the hull-and-pockets region of a concave ring is the plain sweep's region,
the rings are replaced by rings containing them, and the fill of the
Baldacci Test10 fixture is unchanged and valid."""

import os

from shapely.geometry import Polygon

from LeatherCutWorkbench.core.nesting import ContainerSpec, NestOptions, check_layout, nest
from LeatherCutWorkbench.core.nesting.esicup import read_esicup
from LeatherCutWorkbench.core.nesting.hide_shapes import HullPockets, superset_rings
from LeatherCutWorkbench.core.nesting.nfp import inner_fit
from LeatherCutWorkbench.core.nesting.shapes import convex_hull

from nest_shapes import assert_same_fit_region

DATA = os.path.join(os.path.dirname(__file__), "data", "nest")


def _grid(ring, s=10):
    out = [[int(round(s * x)), int(round(s * y))] for x, y in ring]
    return out if Polygon(out).exterior.is_ccw else out[::-1]


def test_hull_and_pockets_give_the_exact_region_of_concave_rings():
    """Concave part outlines (not their hulls) in a concave Baldacci hide
    outline: the same region as the sweep along the outline (to rounding),
    and its vertices put the ring inside the outline."""
    inst = read_esicup(os.path.join(DATA, "Test8.json"))
    ring = _grid(inst.hides[0].outline)
    hp = HullPockets([ring])
    outline = Polygon(ring)
    tried = 0
    for part in inst.parts[:8]:
        b = _grid(part.outer.points())
        if Polygon(b).area >= 0.999 * Polygon(convex_hull(b)).area:
            continue                                  # convex: the old path covers it
        tried += 1
        assert_same_fit_region(hp.ifp(convex_hull(b), b), inner_fit(ring, b), b, outline)
    assert tried >= 2


def test_region_rings_are_replaced_by_rings_containing_them():
    from LeatherCutWorkbench.core.nesting.engine import prepare
    inst = read_esicup(os.path.join(DATA, "Test10_items13_15_hide7.json"))
    opts = NestOptions(container=ContainerSpec.hide(*inst.hides), time_budget=5, workers=1)
    _t, variants, problem, _c, _h, _s = prepare(inst.parts, opts)
    rc = problem.region_check
    seen = 0
    for v in variants:
        if not rc.applies(v.type_index):
            continue
        rings = rc.grid_rings(v.type_index, v.angle, v.mirrored)
        for (g, r), (g2, s) in zip(rings, superset_rings(rings, v)):
            assert g == g2 and Polygon(s).covers(Polygon(r))
            seen += 1
            if len(r) > 40:
                assert len(s) < len(r) / 2
    assert seen


def test_graded_fixture_nests_validly():
    inst = read_esicup(os.path.join(DATA, "Test10_items13_15_hide7.json"))
    opts = NestOptions(container=ContainerSpec.hide(*inst.hides), time_budget=3, workers=1,
                       max_evaluations=3)
    lay = nest(inst.parts, opts)
    assert not lay.unplaced
    assert check_layout(inst.parts, lay) == []


def test_whole_grade_fill_keeps_graded_parts_on_their_strictest_grade():
    """Worker 0's quick first fill (``Placer.whole_grade``) places a part with
    graded regions as if all of it needed its strictest region's grade: the
    coarse fill of the Test10 fixture places every copy without the
    per-position region test, each graded part wholly on material of that
    grade, and the layout passes the checker."""
    from LeatherCutWorkbench.core.nesting.containers import usable_region
    from LeatherCutWorkbench.core.nesting.engine import _to_layout, prepare
    from LeatherCutWorkbench.core.nesting.checker import part_polygon, placed_polygon
    from LeatherCutWorkbench.core.nesting.search import start_orders
    inst = read_esicup(os.path.join(DATA, "Test10_items13_15_hide7.json"))
    opts = NestOptions(container=ContainerSpec.hide(*inst.hides), time_budget=3, workers=1)
    types, variants, problem, copies, hides, scale = prepare(inst.parts, opts)
    rc = problem.region_check
    graded = [t for t in range(len(types)) if rc.applies(t)]
    assert graded
    placer = problem.placer()
    placer.clock.exact_until = -1.0            # coarse, as the quick first fill
    placer.whole_grade = True
    calls = []
    real_ok = rc.ok
    rc.ok = lambda *a: calls.append(a) or real_ok(*a)
    try:
        order = start_orders(problem, copies)[0]
        tr = placer.place(order, abortable=False)
    finally:
        rc.ok = real_ok
    assert not tr.unplaced and not calls
    lay = _to_layout(inst.parts, types, variants, order, tr.placements, opts, scale, hides)
    assert check_layout(inst.parts, lay) == []
    by_id = {p.id: p for p in inst.parts}
    for pl in lay.placements:
        t = next(i for i, ty in enumerate(types) if ty.key == pl.part_id)
        if t in graded:
            g = placed_polygon(part_polygon(by_id[pl.part_id], opts.chord_tol), pl.x, pl.y,
                               pl.angle, pl.mirrored)
            region = usable_region(hides[0], rc.strictest(t))
            assert region.buffer(opts.tolerance).contains(g)
