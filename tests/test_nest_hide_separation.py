"""Overlap minimisation inside a hide (core/nesting/hide_separation.py) on
real Baldacci geometry (tests/data/nest/Test6_items2_10_22_29_hide0.json:
hide o_0 of Test6 with 7 holes and 4 quality-1 zones, forbidden here, and
four of its parts): the container depth is the distance to the inner-fit
region, and a copy the bottom-left fill leaves out is fitted by moving the
others -- checker-valid, also through the copy-to-hide search."""

import math
import os
import random
import time
from dataclasses import replace

import numpy as np
import pyclipper
from shapely.geometry import Point, Polygon
from shapely.ops import unary_union

from LeatherCutWorkbench.core.model import Layout, Placement
from LeatherCutWorkbench.core.nesting import ContainerSpec, NestOptions, check_layout
from LeatherCutWorkbench.core.nesting.engine import _to_layout, prepare
from LeatherCutWorkbench.core.nesting.esicup import read_esicup
from LeatherCutWorkbench.core.nesting.hide_assign import AssignmentSearch, as_layout
from LeatherCutWorkbench.core.nesting.hide_choice import as_hide_indices
from LeatherCutWorkbench.core.nesting.hide_separation import (HideSeparator, _Region,
                                                              container_depths)
from LeatherCutWorkbench.core.nesting.search import _mutate

DATA = os.path.join(os.path.dirname(__file__), "data", "nest")
ANGLES = [0.0, 90.0, 180.0, 270.0]
#: fixture types in file order: i_2, i_10, i_22, i_29; the fill order below
#: (i_2, i_29, i_22, i_10) leaves i_10 out
SEQ = [(0, None), (3, None), (2, None), (1, None)]


def _setup():
    inst = read_esicup(os.path.join(DATA, "Test6_items2_10_22_29_hide0.json"))
    full = inst.hides[0].base_grade
    parts = [replace(p, grade=full, grade_regions=[], quantity=1) for p in inst.parts]
    opts = NestOptions(container=ContainerSpec.hide(*inst.hides), time_budget=60, workers=1,
                       rotations_override=ANGLES, seed=1)
    return parts, opts, prepare(parts, opts)


def _layout(parts, opts, prepared, order, placements):
    types, variants, _problem, _copies, hides, scale = prepared
    return _to_layout(parts, types, variants, order, placements, opts, scale, hides)


def test_container_depth_is_the_distance_to_the_inner_fit_region():
    parts, opts, prepared = _setup()
    types, variants, problem, _copies, hides, scale = prepared
    placer = problem.placer()
    vi = problem.type_variants[3][1]               # i_29 (66 vertices) turned 90 degrees
    rings = placer.hide_ifp(0, vi)
    outers = [Polygon(r) for r in rings if pyclipper.Orientation(r)]
    holes = [Polygon(r) for r in rings if not pyclipper.Orientation(r)]
    fit = unary_union(outers).difference(unary_union(holes)) if holes else unary_union(outers)
    region = _Region([[np.asarray(r, dtype=np.float64) for r in rings]])
    x0, y0, x1, y1 = fit.bounds
    pad = 0.3 * max(x1 - x0, y1 - y0)
    rng = np.random.default_rng(3)
    X = rng.uniform(x0 - pad, x1 + pad, 400)
    Y = rng.uniform(y0 - pad, y1 + pad, 400)
    d = container_depths(X, Y, np.zeros(400, dtype=np.int64), *region.arrays())[:, 0]
    want = np.array([fit.distance(Point(x, y)) for x, y in zip(X, Y)])
    assert np.allclose(d, want, rtol=1e-9, atol=1e-3)
    inside = np.nonzero(d == 0.0)[0]
    assert 20 <= len(inside) <= 380               # points on both sides
    # a copy whose reference point is inside lies on the hide: off the holes and
    # the forbidden zones (the independent checker); one far outside does not
    v = variants[vi]
    for k, expect_ok in [(inside[0], True), (inside[1], True), (int(np.argmax(d)), False)]:
        pl = Placement(part_id=parts[3].id, copy=0, container=hides[0].id,
                       x=X[k] / scale, y=Y[k] / scale, angle=v.angle, mirrored=v.mirrored)
        lay = Layout(containers=list(hides), placements=[pl], unplaced=[], metrics={})
        assert (check_layout(parts, lay, rotations_override=ANGLES) == []) == expect_ok


def test_separator_fits_the_copy_the_fill_left_out():
    parts, opts, prepared = _setup()
    types, variants, problem, _copies, hides, scale = prepared
    placer = problem.placer()
    tr = placer.place(SEQ)
    assert tr.unplaced == [3]                       # i_10 found no place
    placed = [(SEQ[si][0], vi, x, y) for (si, b, vi, x, y) in tr.placements if b >= 0]
    out = HideSeparator(placer, problem.type_area, 1.0).fit(0, placed, [1],
                                                            time.monotonic() + 30.0, seed=2)
    assert out is not None and [c[0] for c in out] == [0, 3, 2, 1]
    lay = _layout(parts, opts, prepared, [(c[0], c[1]) for c in out],
                  [(k, 0, c[1], c[2], c[3]) for k, c in enumerate(out)])
    assert check_layout(parts, lay, rotations_override=ANGLES) == []
    assert lay.metrics["placed_count"] == 4 and lay.metrics["unplaced_count"] == 0


def test_copy_to_hide_search_repairs_a_left_out_copy_and_refills_after_it():
    """``AssignmentSearch._repair`` on the one-hide set: every copy placed,
    checker-valid; a later re-fill of that hide from position 2 keeps the two
    separated copies in front and fills the rest into the gaps (valid too)."""
    parts, opts, prepared = _setup()
    types, variants, problem, _copies, hides, scale = prepared
    s = AssignmentSearch(problem, problem.placer(), random.Random(5), _mutate, lambda: False)
    st = s.start([0], [list(SEQ)])
    assert st.total > 0 and len(st.traces[0].unplaced) == 1
    fixed = s._repair(st)
    assert fixed is not None and fixed.total == 0 and s.repairs == [1, 1]
    seq, placements, order = as_layout(fixed)
    lay = _layout(parts, opts, prepared, seq, as_hide_indices(placements, order))
    assert check_layout(parts, lay, rotations_override=ANGLES) == []
    assert lay.metrics["unplaced_count"] == 0
    assert s._fill(fixed, 0, 2, math.inf)
    assert fixed.traces[0].placements[:2] == placements[:2]
    seq, placements, order = as_layout(fixed)
    lay = _layout(parts, opts, prepared, seq, as_hide_indices(placements, order))
    assert check_layout(parts, lay, rotations_override=ANGLES) == []


def test_no_container_depth_is_zero_beyond_the_far_box_of_the_complement():
    """The complement of a region ends at a far box; a point pushed beyond
    it (the complement's nearest edge is the box) must stay deep, and an
    empty region (a variant that fits nowhere) has no point of depth 0."""
    sq = np.array([[0.0, 0.0], [10.0, 0.0], [10.0, 10.0], [0.0, 10.0]])
    region = _Region([[sq], []])
    box = region.bbox[0]
    X = np.array([5.0, 20.0, box[0] + 1.0, box[0] - 1.0, box[2] + 1e3, 5.0, box[0] - 1.0])
    Y = np.array([5.0, 5.0, 5.0, 5.0, 5.0, 5.0, 5.0])
    V = np.array([0, 0, 0, 0, 0, 1, 1], dtype=np.int64)
    d = container_depths(X, Y, V, *region.arrays())[:, 0]
    assert d[0] == 0.0 and abs(d[1] - 10.0) < 1e-9
    assert (d[2:] > 0.0).all()                       # near the box, beyond it, empty region
    assert d[3] >= d[2] and d[4] >= d[2]             # beyond the box: deeper than just inside


def test_separator_keeps_a_copy_whose_hull_fits_nowhere_on_the_hide():
    """Test6 hide o_5 and part i_33 turned 330 degrees: its convex hull fits
    nowhere on the hide, its own outline does (the fill places it with
    ``concave_fit``).  Its separation region is the exact one, so when a copy
    of i_22 is fitted next to it, it stays where the fill put it.  With the
    hull's region (empty) its container depth was the distance to the far box
    of the region's complement: the separator pushed it out of the box (to
    x = -7.6e11 grid units in a Test6 run) and called it fitted; the engine's
    checker then left it out of a 60 s Test6 layout (42/43)."""
    inst = read_esicup(os.path.join(DATA, "Test6_items22_33_hide5.json"))
    full = inst.hides[0].base_grade
    parts = [replace(p, grade=full, grade_regions=[], quantity=1) for p in inst.parts]
    angles = [float(a) for a in range(0, 360, 30)]
    opts = NestOptions(container=ContainerSpec.hide(*inst.hides), time_budget=60, workers=1,
                       rotations_override=angles, seed=1)
    types, variants, problem, _copies, hides, scale = prepare(parts, opts)
    placer = problem.placer()
    placer.concave_fit = True
    hull_less = [vi for vi in problem.type_variants[1] if not placer.hide_ifp(0, vi)
                 and placer.hide_ifp(0, vi, concave=True)]
    assert len(hull_less) == 1 and variants[hull_less[0]].angle == 330.0
    vi = hull_less[0]
    tr = placer.place([(1, vi)])
    (_si, b, v, x, y), = tr.placements
    assert b == 0 and v == vi
    out = HideSeparator(placer, problem.type_area, 1.0).fit(0, [(1, vi, x, y)], [0],
                                                            time.monotonic() + 20.0, seed=1)
    assert out is not None and out[0] == (1, vi, x, y)
    lay = _to_layout(parts, types, variants, [(c[0], c[1]) for c in out],
                     [(k, 0, c[1], c[2], c[3]) for k, c in enumerate(out)], opts, scale, hides)
    assert check_layout(parts, lay, rotations_override=angles) == []
