"""Which hides to use: fewest hides first, then the best utilisation of the
hides used (the smallest net area that holds every copy), whatever the
order of the hides in the file."""

import os
from dataclasses import replace

from LeatherCutWorkbench.core.model import Container
from LeatherCutWorkbench.core.nesting import ContainerSpec, NestOptions, check_layout, nest
from LeatherCutWorkbench.core.nesting.containers import net_area
from LeatherCutWorkbench.core.nesting.esicup import read_esicup

from nest_shapes import assert_same_fit_region

DATA = os.path.join(os.path.dirname(__file__), "data", "nest")
ANGLES = [0.0, 90.0, 180.0, 270.0]


def _hides_and_parts():
    """Baldacci Test8's hide outline (2.5 m^2) at 1.6x and 1x size, the big one
    first in the file; a third of Test8's copies (fit on the small hide)."""
    inst = read_esicup(os.path.join(DATA, "Test8.json"))
    outline = inst.hides[0].outline
    big = Container(id="big", kind="hide", outline=[(1.6 * x, 1.6 * y) for x, y in outline],
                    base_grade=1)
    small = Container(id="small", kind="hide", outline=list(outline), base_grade=1)
    parts = [replace(p, grade=1, grade_regions=[], quantity=max(1, p.quantity // 3))
             for p in inst.parts]
    return [big, small], parts


def test_the_smaller_hide_that_holds_every_copy_is_chosen():
    hides, parts = _hides_and_parts()
    opts = NestOptions(container=ContainerSpec.hide(*hides), time_budget=60, workers=1,
                       max_evaluations=150, rotations_override=ANGLES, seed=3)
    lay = nest(parts, opts)
    assert check_layout(parts, lay, rotations_override=ANGLES) == []
    m = lay.metrics
    assert m["unplaced_count"] == 0 and m["hides"] == 1
    # the big hide comes first in the file (and first in the initial fill order)
    assert [c.id for c in lay.containers] == ["small"]
    area = sum(p.net_area * p.quantity for p in parts)
    assert abs(m["utilisation"] - area / net_area(hides[1])) < 1e-4
    assert m["per_container"][0]["id"] == "small"


def test_fewest_hides_before_utilisation():
    """Every copy of Test8 (1.82 m^2) on two 1.6 m^2 hides (0.8x Test8's
    outline) would give a higher utilisation than on the 6.4 m^2 one alone
    (57 % against 28 %), but one hide is fewer."""
    hides, _parts = _hides_and_parts()
    inst = read_esicup(os.path.join(DATA, "Test8.json"))
    parts = [replace(p, grade=1, grade_regions=[]) for p in inst.parts]
    small = [Container(id=f"small{k}", kind="hide", base_grade=1,
                       outline=[(0.8 * x, 0.8 * y) for x, y in hides[1].outline]) for k in (1, 2)]
    spec = ContainerSpec.hide(small[0], small[1], hides[0])
    opts = NestOptions(container=spec, time_budget=60, workers=1, max_evaluations=60,
                       rotations_override=ANGLES, seed=3)
    lay = nest(parts, opts)
    assert check_layout(parts, lay, rotations_override=ANGLES) == []
    assert lay.metrics["unplaced_count"] == 0
    assert [c.id for c in lay.containers] == ["big"]


def test_simplified_hide_outlines_contain_the_parts_and_have_fewer_vertices():
    """A finely flattened seat-like part (a 200-vertex crescent): the ring hide
    nesting uses contains the true one, has far fewer vertices and is less
    than 1.5 % larger (a thin crescent: much outline per area)."""
    import math

    from shapely.geometry import Polygon

    from LeatherCutWorkbench.core.nesting.hide_shapes import HIDE_SIMPLIFY, simplify_for_hides
    from LeatherCutWorkbench.core.nesting.shapes import make_variants, piece_from_part
    from LeatherCutWorkbench.core.model import Part
    from nest_shapes import poly_contour

    outer = [(600 * math.cos(a), 300 * math.sin(a)) for a in
             (math.pi * k / 100 for k in range(101))]
    inner = [(400 * math.cos(a), 120 * math.sin(a)) for a in
             (math.pi * (100 - k) / 100 for k in range(1, 100))]
    part = Part(id="crescent", outer=poly_contour("o", outer + inner))
    t = piece_from_part(part, 0.05, 30.0, [0.0, 90.0], False)
    variants = make_variants([t], 1000.0, 0.0, 0.05)
    for v, s in zip(variants, simplify_for_hides(variants)):
        true, simple = Polygon(v.outer), Polygon(s.outer)
        assert simple.covers(true) and Polygon(s.core).covers(Polygon(v.core))
        assert len(s.outer) < len(v.outer) / 3
        # grown by at most HIDE_SIMPLIFY x the part's size all round (mitred corners)
        d = HIDE_SIMPLIFY * max(v.bbox[2] - v.bbox[0], v.bbox[3] - v.bbox[1])
        assert simple.area - true.area < 1.1 * d * true.exterior.length
        assert simple.area < 1.04 * true.area


def test_hull_and_pockets_give_the_inner_fit_region_of_the_hide_outline():
    """On a real Baldacci hide outline (Test8, concave), the inner-fit region
    of convex part hulls from the hide's hull minus its pockets is the region
    the plain sweep along the outline gives (to rounding), and its vertices
    put the part inside the outline."""
    from shapely.geometry import Polygon

    from LeatherCutWorkbench.core.nesting.hide_shapes import HullPockets
    from LeatherCutWorkbench.core.nesting.nfp import inner_fit
    from LeatherCutWorkbench.core.nesting.shapes import convex_hull

    inst = read_esicup(os.path.join(DATA, "Test8.json"))
    ring = [[int(round(10 * x)), int(round(10 * y))] for x, y in inst.hides[0].outline]
    if Polygon(ring).exterior.is_ccw is False:
        ring = ring[::-1]
    hp = HullPockets([ring])
    assert hp.parts[0][1], "the hide outline is concave: it has pockets"
    outline = Polygon(ring)
    for part in inst.parts[:6]:
        hull = convex_hull([[int(round(10 * x)), int(round(10 * y))]
                            for x, y in part.outer.points()])
        assert_same_fit_region(hp.ifp(hull), inner_fit(ring, hull), hull, outline)


def test_hide_cost_prefers_the_layout_closer_to_emptying_a_hide():
    """Same copies on the same two hides: the layout with less part area on
    its least-filled hide ranks better (whatever the extent of the last hide);
    fewer hides and a smaller net area still come first."""
    from LeatherCutWorkbench.core.nesting.hide_choice import hide_cost

    net = [100.0, 80.0, 60.0]
    areas = [30.0, 20.0, 10.0]
    balanced = [(0, 0, 0, 0, 0), (1, 1, 0, 0, 0), (2, 1, 0, 0, 0)]   # hide 1 holds 30
    lopsided = [(0, 0, 0, 0, 0), (1, 0, 0, 0, 0), (2, 1, 0, 0, 0)]   # hide 1 holds 10
    order = [0, 1, 2]
    assert hide_cost(lopsided, order, net, 0.0, 90, areas) < \
        hide_cost(balanced, order, net, 0.0, 10, areas)
    one_hide = [(0, 0, 0, 0, 0), (1, 0, 0, 0, 0), (2, 0, 0, 0, 0)]
    assert hide_cost(one_hide, order, net, 0.0, 99, areas) < hide_cost(lopsided, order, net, 0.0, 0, areas)
    smaller = [(0, 0, 0, 0, 0), (1, 0, 0, 0, 0), (2, 1, 0, 0, 0)]
    assert hide_cost(smaller, [0, 2, 1], net, 0.0, 0, areas) < \
        hide_cost(balanced, order, net, 0.0, 0, [30.0, 1.0, 1.0])


def test_swap_puts_a_smaller_hide_in_place_of_the_least_filled_one():
    """Two used hides (position 1 holds little), five unused ones, one of them
    smaller than hide 1: about half of the swaps put that one at position 1
    (a random swap would do so in about one of twenty)."""
    import random

    from LeatherCutWorkbench.core.nesting.hide_choice import swap_hides

    net = [90.0, 80.0, 70.0, 95.0, 96.0, 97.0, 98.0]
    order = list(range(7))
    placements = [(0, 0, 0, 0, 0), (1, 0, 0, 0, 0), (2, 1, 0, 0, 0)]
    areas = [40.0, 30.0, 5.0]
    hits = 0
    for seed in range(200):
        new, first = swap_hides(random.Random(seed), order, placements, net, areas)
        assert sorted(new) == order and first == min(p for p in range(7) if new[p] != order[p])
        hits += new[1] == 2
    assert hits >= 80


def test_gravity_y_fills_a_hide_bottom_up():
    """Three 40 x 10 bars on a 100 x 100 hide: left-to-right gravity stacks
    them at x = 0 (smallest right edge), bottom-up gravity lays them side by
    side along y = 0 before it starts a second row."""
    from LeatherCutWorkbench.core.nesting.blf import BinSpec, Placer
    from LeatherCutWorkbench.core.nesting.shapes import make_variants, piece_from_part
    from nest_shapes import rect

    types = [piece_from_part(rect("bar", 40, 10), 0.05, 90.0, [0.0])]
    vs = make_variants(types, 1000.0, 0.0, 0.05)
    square = [[0, 0], [100000, 0], [100000, 100000], [0, 100000]]
    spec = BinSpec("hide", regions={1: ([square], [])}, grade_key={1: 1})
    got = {}
    for g in ("x", "y"):
        placer = Placer(vs, [[v.index for v in vs]], [1], [spec], False, 1)
        placer.gravity = g
        tr = placer.place([(0, None)] * 3, abortable=False)
        got[g] = [(round((tx + vs[vi].bbox[0]) / 1000), round((ty + vs[vi].bbox[1]) / 1000))
                  for (_si, _b, vi, tx, ty) in tr.placements]
    assert got["x"] == [(0, 0), (0, 10), (0, 20)]
    assert got["y"] == [(0, 0), (40, 0), (0, 10)]
