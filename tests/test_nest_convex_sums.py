"""The compiled batch of convex Minkowski sums gives exactly the rings of the
one-by-one numpy sum, and the no-fit polygons of real leather parts built
from it are the true Minkowski sums (area checked against shapely)."""

import os
import random

from shapely.geometry import MultiPoint, Polygon
from shapely.ops import unary_union

from LeatherCutWorkbench.core.nesting.checker import part_polygon
from LeatherCutWorkbench.core.nesting.convex import convex_pieces, edge_form, sum_forms
from LeatherCutWorkbench.core.nesting import convex_sums
from LeatherCutWorkbench.core.nesting.convex_sums import FormSet, sum_all, warm_up
from LeatherCutWorkbench.core.nesting.esicup import read_esicup
from LeatherCutWorkbench.core.nesting.nfp import _neg, piece_forms, solid_nfp
from LeatherCutWorkbench.core.nesting.shapes import convex_hull

DATA = os.path.join(os.path.dirname(__file__), "data", "nest")


def _random_convex(rng, n):
    pts = [[rng.randrange(-500, 500), rng.randrange(-500, 500)] for _ in range(n)]
    return convex_hull(pts)


def test_batch_sums_equal_the_numpy_sums_vertex_for_vertex():
    rng = random.Random(5)
    a = [edge_form(_random_convex(rng, rng.randrange(3, 30))) for _ in range(7)]
    b = [edge_form(_random_convex(rng, rng.randrange(3, 30))) for _ in range(5)]
    # axis-parallel squares: equal edge angles in both (the tie order matters)
    sq = [[0, 0], [10, 0], [10, 10], [0, 10]]
    a.append(edge_form(sq))
    b.append(edge_form([[p[0] * 3 + 7, p[1] * 3 - 2] for p in sq]))
    warm_up()
    assert convex_sums._kernel is not None
    got = sum_all(FormSet(a), b)
    want = [sum_forms(x, y) for x in a for y in b]
    assert got == want
    assert sum_all(FormSet([]), b) == []


def test_sums_before_the_kernel_is_loaded_are_the_kernels(monkeypatch):
    """Worker 0's first fill on hides runs before :func:`warm_up` (numba not
    imported yet): its pair-by-pair sums of the convex pieces of the two most
    concave Test1 parts (one negated, as in a no-fit polygon) are the
    kernel's rings."""
    inst = read_esicup(os.path.join(DATA, "Test1_first2hides.json"))
    rings = []
    for p in inst.parts:
        g = part_polygon(p, 0.1)
        r = [[int(round(x * 10)), int(round(y * 10))] for x, y in g.exterior.coords[:-1]]
        rings.append(r if Polygon(r).exterior.is_ccw else r[::-1])
    a, b = sorted(rings, key=lambda r: -len(piece_forms(r)))[:2]
    forms = [piece_forms(a), piece_forms(b, negate=True)]
    warm_up()
    compiled = sum_all(forms[0], forms[1])
    monkeypatch.setattr(convex_sums, "_kernel", None)
    assert sum_all(forms[0], forms[1]) == compiled and len(compiled) > 4


def test_leather_part_nfp_is_the_exact_minkowski_sum():
    """Two Baldacci Test1 parts (concave, 60-100 vertices): the union of the
    batch piece sums has the area of shapely's union of all vertex-pair hulls
    of the convex pieces (an independent construction of A (+) -B)."""
    inst = read_esicup(os.path.join(DATA, "Test1_first2hides.json"))
    rings = []
    for p in inst.parts[:2]:
        g = part_polygon(p, 0.1)
        r = [[int(round(x * 10)), int(round(y * 10))] for x, y in g.exterior.coords[:-1]]
        rings.append(r if Polygon(r).exterior.is_ccw else r[::-1])
    a, b = rings
    nfp = solid_nfp(a, b, piece_forms(a), piece_forms(b, negate=True))
    assert len(nfp) == 1
    ref = unary_union([MultiPoint([(x + u, y + v) for x, y in pa for u, v in _neg(pb)]).convex_hull
                       for pa in convex_pieces(a) for pb in convex_pieces(b)])
    assert abs(Polygon(nfp[0]).area - ref.area) <= 1e-6 * ref.area
