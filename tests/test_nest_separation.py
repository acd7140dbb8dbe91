"""The strip improvement phase (overlap penetration depth, separator, shrink
loop) on real geometry: the ESICUP instance fu and real parts with holes.
Every returned layout is re-checked with the independent checker."""

import os
import time

import numpy as np
import pytest

from LeatherCutWorkbench.core.errors import CancelledError
from LeatherCutWorkbench.core.model import Container, Layout, Placement
from LeatherCutWorkbench.core.nesting import ContainerSpec, NestOptions, check_layout, nest
from LeatherCutWorkbench.core.nesting.engine import fill_metrics
from LeatherCutWorkbench.core.nesting.esicup import read_esicup
from LeatherCutWorkbench.core.nesting.overlap import PairTable, copy_penalty, pair_depth
from LeatherCutWorkbench.core.nesting.shapes import make_variants, piece_from_part
from LeatherCutWorkbench.core.nesting.separation import Separator, colliding_total, seed_rng
from LeatherCutWorkbench.core.nesting.strip_shrink import (_Best, _explore, _Instance, _search_share,
                                                         _swap_large,
                                                         improve_last_sheet,
                                                         improve_strip, nest_compacted)

from nest_shapes import frame, rect

DATA = os.path.join(os.path.dirname(__file__), "data", "nest")


def _fu():
    inst = read_esicup(os.path.join(DATA, "fu.json"))
    opts = NestOptions(container=ContainerSpec.strip(inst.strip_height), time_budget=0.5,
                       max_evaluations=8, seed=1, workers=1)
    return inst.parts, opts


def _valid(parts, lay, opts):
    return check_layout(parts, lay, spacing=opts.spacing, margin=opts.margin)


def _loose_row(parts, opts, gap):
    """Every copy at angle 0 in one row along the strip, ``gap`` mm apart: valid, loose."""
    placements, x = [], 0.0
    for p in parts:
        x0, y0, x1, y1 = p.outer.bbox
        for k in range(p.quantity):
            placements.append(Placement(part_id=p.id, copy=k, container="strip",
                                        x=x - x0 + opts.margin, y=opts.margin - y0, angle=0.0))
            x += (x1 - x0) + gap
    lay = Layout(containers=[Container(id="strip", kind="strip", outline=[])],
                 placements=placements)
    fill_metrics(parts, lay, opts)
    return lay


@pytest.fixture(scope="module", autouse=True)
def compiled_kernels():
    """Compile the numba kernels before the timed tests (the first compile on a
    fresh checkout takes seconds, which would eat a test's deadline)."""
    parts, opts = _fu()
    inst = _Instance(_loose_row(parts, opts, gap=1.0), parts, opts)
    tab = PairTable(inst.variants)
    Separator(tab, inst.cb, inst.choices, inst.types, inst.y0, inst.y1, inst.x0,
              inst.eps).warm_up(inst.X, inst.Y, inst.V, inst.right_edge(inst.X, inst.V))


def test_penetration_depth_of_two_squares_is_the_shortest_separating_move():
    sq = rect("s", 10, 10)
    scale = 1000.0                         # grid units per mm
    v = make_variants([piece_from_part(sq, 0.05, 90, [0])], scale, 0.0, 0.05)
    tab = PairTable(v)
    arrs = tab.arrays()
    # B 7 mm right and 2 mm up of A: pushing it 3 mm right separates them
    assert pair_depth(7000.0, 2000.0, 0, *arrs) == pytest.approx(3000.0, abs=3.0)
    assert pair_depth(1000.0, -9000.0, 0, *arrs) == pytest.approx(1000.0, abs=3.0)
    assert pair_depth(10010.0, 0.0, 0, *arrs) == 0.0        # 10 microns apart: no overlap
    assert pair_depth(0.0, 0.0, 0, *arrs) == pytest.approx(10000.0, abs=3.0)


def test_depth_is_zero_for_a_part_inside_the_hole_of_another():
    fr = frame("F", 100, 100, 10)          # hole 80 x 80 mm
    small = rect("s", 20, 20)
    pieces = [piece_from_part(p, 0.05, 90, [0]) for p in (fr, small)]
    v = make_variants(pieces, 100.0, 0.0, 0.05)
    tab = PairTable(v)
    p = 0 * tab.n + 1                      # the square around the fixed frame
    assert pair_depth(4000.0, 4000.0, p, *tab.arrays()) == 0.0           # inside the hole
    assert pair_depth(500.0, 4000.0, p, *tab.arrays()) > 400.0           # on the frame's bar


def _penalty_of_first(tab, X, ramp=1.0):
    """Cost of copy 0 of three unit-weight copies of variant 0 (all at y = 0)."""
    X = np.asarray(X, dtype=np.float64)
    Y, V, W = np.zeros(3), np.zeros(3, dtype=np.int64), np.ones(3)
    order = np.argsort(X)
    return copy_penalty(0, 0, X[0], 0.0, X, Y, V, W, 1, 1e300, order, X[order], -1e9, 1e9,
                        *tab.costs(), ramp, *tab.arrays())


def test_two_shallow_overlaps_cost_more_than_one_overlap_of_their_summed_depth():
    # the search must prefer fewer overlapping pairs: with cost = depth alone, two
    # 0.5 mm overlaps and one 1 mm overlap cost the same and shallow overlaps pile up
    v = make_variants([piece_from_part(rect("s", 10, 10), 0.05, 90, [0])], 1000.0, 0.0, 0.05)
    tab = PairTable(v)
    d = 500.0
    two = _penalty_of_first(tab, [10000.0 - d, 0.0, 20000.0 - 2 * d])
    one = _penalty_of_first(tab, [10000.0 - 2 * d, 0.0, 50000.0])
    assert two > one * 1.05
    # contact (depth within the ramp) stays nearly free, no overlap costs nothing;
    # c = the distance at which the (slightly grown) outlines touch
    c = pair_depth(0.0, 0.0, 0, *tab.arrays())
    assert _penalty_of_first(tab, [c - 0.2, 0.0, 50000.0], ramp=50.0) < 1.0
    assert _penalty_of_first(tab, [c - 100.0, 0.0, 50000.0], ramp=50.0) > 200.0
    assert _penalty_of_first(tab, [c + 1.0, 0.0, 50000.0]) == 0.0


def test_engine_search_share_falls_with_many_copies():
    assert _search_share([rect("a", 5, 5, q=24)]) == pytest.approx(0.25)
    assert _search_share([rect("a", 5, 5, q=50), rect("b", 5, 5, q=49)]) == pytest.approx(0.101, abs=1e-3)
    assert _search_share([rect("a", 5, 5, q=1000)]) == pytest.approx(0.08)


def test_engine_layout_is_never_made_invalid_or_longer():
    parts, opts = _fu()
    lay = nest(parts, opts)
    before = lay.metrics["strip_length_mm"]
    new = improve_strip(lay, parts, opts, time.monotonic() + 4.0)
    assert _valid(parts, new, opts) == []
    assert new.unplaced == [] and len(new.placements) == len(lay.placements)
    assert new.metrics["strip_length_mm"] <= before
    assert new.metrics["density"] >= lay.metrics["density"]


def test_loose_layout_shrinks_a_lot_and_stays_valid_with_spacing_and_margin():
    parts, opts = _fu()
    opts.spacing, opts.margin = 0.5, 1.0
    loose = _loose_row(parts, opts, gap=3.0)
    assert _valid(parts, loose, opts) == []
    before = loose.metrics["strip_length_mm"]
    new = improve_strip(loose, parts, opts, time.monotonic() + 4.0)
    assert _valid(parts, new, opts) == []
    assert len(new.placements) == len(loose.placements)
    # one row of 12 copies is > 3x longer than a packed strip: expect far less than half
    assert new.metrics["strip_length_mm"] < 0.5 * before
    assert new.metrics["strip_improved_from_mm"] == pytest.approx(before)


def test_parts_with_holes_can_take_a_copy_in_the_hole():
    parts = [frame("F", 60, 60, 8, q=2), rect("s", 30, 30, q=2, rotations=[0])]
    opts = NestOptions(container=ContainerSpec.strip(60), workers=1)
    loose = _loose_row(parts, opts, gap=5.0)
    new = improve_strip(loose, parts, opts, time.monotonic() + 4.0)
    assert _valid(parts, new, opts) == []
    # the frames need 120 mm side by side; the squares only fit without growing it in the holes
    assert new.metrics["strip_length_mm"] < 121.0


def test_other_containers_and_incomplete_layouts_come_back_unchanged():
    parts, opts = _fu()
    lay = nest(parts, opts)
    sheet = NestOptions(container=ContainerSpec.sheet(100, 40), workers=1)
    assert improve_strip(lay, parts, sheet, time.monotonic() + 1.0) is lay
    lay.unplaced.append((parts[0].id, 99))
    assert improve_strip(lay, parts, opts, time.monotonic() + 1.0) is lay
    assert np.isfinite(lay.metrics["strip_length_mm"])


def test_two_workers_and_cancel():
    parts, opts = _fu()
    opts.workers = 2
    loose = _loose_row(parts, opts, gap=2.0)
    new = improve_strip(loose, parts, opts, time.monotonic() + 4.0)
    assert _valid(parts, new, opts) == []
    assert new.metrics["strip_length_mm"] < 0.5 * loose.metrics["strip_length_mm"]
    t0 = time.monotonic()
    with pytest.raises(CancelledError):
        improve_strip(loose, parts, opts, time.monotonic() + 30.0, progress=lambda f, m: False)
    assert time.monotonic() - t0 < 10.0          # the workers stop at their next sweep


def test_last_sheet_gets_shorter_and_the_first_sheet_stays():
    parts = [rect("a", 48, 48, q=2, rotations=[0]), rect("b", 20, 20, q=4, rotations=[0])]
    opts = NestOptions(container=ContainerSpec.sheet(100, 50), workers=1)
    pls = [Placement(part_id="a", copy=k, container="sheet1", x=50.0 * k, y=0.0) for k in range(2)]
    pls += [Placement(part_id="b", copy=k, container="sheet2", x=25.0 * k, y=0.0) for k in range(4)]
    sheets = [Container(id=f"sheet{k}", kind="sheet", outline=[(0, 0), (100, 0), (100, 50), (0, 50)])
              for k in (1, 2)]
    lay = Layout(containers=sheets, placements=pls)
    fill_metrics(parts, lay, opts)
    assert _valid(parts, lay, opts) == []
    new = improve_last_sheet(lay, parts, opts, time.monotonic() + 4.0)
    assert _valid(parts, new, opts) == []
    per = {c["id"]: c for c in new.metrics["per_container"]}
    assert per["sheet2"]["used_length_mm"] < 60.0          # was 95: two columns of two fit in 40
    assert [(p.x, p.y) for p in new.placements if p.container == "sheet1"] == [(0.0, 0.0), (50.0, 0.0)]


def test_nest_compacted_on_sheets_keeps_the_sheet_count_and_is_valid():
    parts = [rect("a", 60, 40, q=7, rotations=[0, 90])]
    opts = NestOptions(container=ContainerSpec.sheet(130, 90), time_budget=3.0, workers=1)
    lay = nest_compacted(parts, opts)
    assert _valid(parts, lay, opts) == [] and lay.unplaced == []
    assert lay.metrics["sheets"] == 2                 # 4 per sheet at most
    assert lay.metrics["time_s"] <= 3.0 + 0.1 * 3.0 + 1.0


def test_inflated_outlines_keep_half_the_spacing_at_corners():
    # pyclipper gives a 90-degree round join one chord; it cut the corner to 0.212 mm
    # of a 0.25 mm half gap, and the separator put two corners 0.49 mm apart
    from shapely.geometry import Polygon
    from LeatherCutWorkbench.core.nesting.shapes import transform_ring
    parts = [rect("r", 5, 9, rotations=[0, 90])]
    opts = NestOptions(container=ContainerSpec.strip(20), spacing=0.5, workers=1)
    loose = _loose_row(parts, opts, gap=1.0)
    inst = _Instance(loose, parts, opts)
    for v in inst.variants:
        true = Polygon(transform_ring(inst.pieces[0].outer, v.angle, v.mirrored))
        grown = Polygon(np.asarray(v.outer, dtype=float) / inst.scale)
        assert grown.contains(true)
        assert true.exterior.distance(grown.exterior) >= 0.25


def test_depth_agrees_with_shapely_on_the_concave_pieces_of_fu():
    # the branch-free winding test of pair_depth against an independent overlap test:
    # every pair of fu's oriented pieces at random translations; near-contact cases skipped
    from shapely.affinity import translate
    from shapely.geometry import Polygon
    parts, opts = _fu()
    inst = _Instance(_loose_row(parts, opts, gap=1.0), parts, opts)
    tab = PairTable(inst.variants)
    poly = [Polygon(np.asarray(v.outer, dtype=float)) for v in inst.variants]
    rng = np.random.default_rng(3)
    checked = inside = 0
    while checked < 400:
        a, b = (int(k) for k in rng.integers(tab.n, size=2))
        x0, y0, x1, y1 = tab.bbox[a * tab.n + b]
        tx, ty = rng.uniform(x0, x1), rng.uniform(y0, y1)
        moved = translate(poly[b], tx, ty)
        d = pair_depth(tx, ty, a * tab.n + b, *tab.arrays())
        gap = poly[a].distance(moved)
        area = poly[a].intersection(moved).area
        if gap > 50.0:
            assert d == 0.0
        elif area > 1e-3 * poly[b].area:
            assert d > 0.0
            if inside < 20:
                # the depth is the shortest separating push: at most the shortest
                # axis-aligned one (searched in 1 % steps of the pair's reach)
                step = 0.01 * max(x1 - x0, y1 - y0)
                s = next(k * step for k in range(1, 101)
                         if any(not poly[a].intersects(translate(moved, dx, dy))
                                for dx, dy in ((k * step, 0), (-k * step, 0), (0, k * step), (0, -k * step))))
                assert d <= s + 1.0
            inside += 1
        else:
            continue
        checked += 1
    assert inside > 50


def test_separation_gives_up_when_asked_and_keeps_the_least_overlap():
    parts, opts = _fu()
    inst = _Instance(_loose_row(parts, opts, gap=1.0), parts, opts)
    sep = Separator(PairTable(inst.variants), inst.cb, inst.choices, inst.types, inst.y0,
                    inst.y1, inst.x0, inst.eps)
    X, Y, V = inst.X.copy(), inst.Y.copy(), inst.V.copy()
    x1 = inst.x0 + 0.3 * (inst.right_edge(X, V) - inst.x0)     # far too short: cannot succeed
    X[:] = np.minimum(X, x1 - inst.cb[V, 2])
    start = sep.overlaps(X, Y, V).sum()
    asked = []
    ok = sep.separate(X, Y, V, x1, time.monotonic() + 30.0, give_up=lambda: asked.append(1) or True)
    assert not ok and len(asked) == 1                          # one sweep, then it stopped
    assert 0.0 < sep.overlaps(X, Y, V).sum() <= start


def test_engine_search_ends_at_its_plateau():
    from LeatherCutWorkbench.core.nesting.strip_shrink import _Stall
    seen = []
    stall = _Stall(0.2, seen.append, None)
    assert not stall.stop()                       # no layout yet: never stops
    stall.on_best("layout")
    assert not stall.stop() and seen == ["layout"]
    time.sleep(0.3)
    assert stall.stop()
    user = _Stall(100.0, None, lambda: True)
    assert user.stop()                            # the user's Stop always counts
    # sheets: no plateau counts before the other workers' first fills had their time
    late = _Stall(0.05, None, None, not_before=time.monotonic() + 0.4)
    late.on_best("layout")
    time.sleep(0.15)
    assert not late.stop()
    time.sleep(0.3)
    assert late.stop()


def _exploring(lay, parts, opts):
    """(instance, separator, shared best) of the strip phase started from ``lay``."""
    inst = _Instance(lay, parts, opts)
    sep = Separator(PairTable(inst.variants), inst.cb, inst.choices, inst.types, inst.y0,
                    inst.y1, inst.x0, inst.eps, pad=inst.pad)
    return inst, sep, _Best((inst.right_edge(inst.X, inst.V), inst.X, inst.Y, inst.V))


def test_exploration_retries_from_its_own_failed_layout_inside_the_strip():
    """Exploration (sparrow's): after a failed separation the worker does not
    go back to the best valid layout; its next try starts from the layout that
    failure left (two large copies swapped, with the copies they cover), still below
    the best and inside the strip.  Every layout it keeps passes the checker."""
    parts, opts = _fu()
    lay = nest(parts, opts)
    inst, sep, shared = _exploring(lay, parts, opts)
    calls = []
    real = sep.separate

    def recording(X, Y, V, x1, *a, **k):
        cb = inst.cb[V]
        inside = bool((X + cb[:, 0] >= inst.x0 - 1e-6).all() and (X + cb[:, 2] <= x1 + 1e-6).all()
                      and (Y + cb[:, 1] >= inst.y0 - 1e-6).all() and (Y + cb[:, 3] <= inst.y1 + 1e-6).all())
        start, best = (X.copy(), Y.copy()), shared.get()[0]
        ok = real(X, Y, V, x1, *a, **k)
        calls.append(dict(x1=x1, best=best, ok=ok, inside=inside, start=start, end=(X.copy(), Y.copy())))
        return ok
    sep.separate = recording
    found: list = []
    _explore(inst, sep, shared, time.monotonic() + 3.0, np.random.default_rng(1), found)
    assert calls and all(c["inside"] and c["x1"] < c["best"] for c in calls)
    retries = [(a, b) for a, b in zip(calls, calls[1:]) if not a["ok"] and b["best"] == a["best"]]
    assert retries, "no failed separation in 3 s"
    for a, b in retries[:1]:                      # a pool of one: the retry starts from it
        moved = (np.abs(a["end"][0] - b["start"][0]) > 1e-9) | (np.abs(a["end"][1] - b["start"][1]) > 1e-9)
        assert 2 <= moved.sum() <= len(moved) // 2    # the swapped pair and the copies it carries
    assert found
    for x1, X, Y, V in found:
        new = inst.to_layout(lay, X, Y, V)
        fill_metrics(parts, new, opts)
        assert _valid(parts, new, opts) == []
        assert new.metrics["strip_length_mm"] < lay.metrics["strip_length_mm"]


def test_exploration_keeps_its_target_and_a_retry_from_the_pool_separates_on_albano():
    """Exploration on albano (ESICUP, 24 garment copies): after failed
    separations the target does not move up (sparrow's fixed shrink; the
    previous loop moved it up after two failures in a row): each retry starts
    from an overlapping layout of the pool at the same length ``x1``.  The
    first retry that separates after two failures gives a layout the checker
    passes, no longer than ``x1`` and so shorter than the best valid layout it
    started below."""
    inst0 = read_esicup(os.path.join(DATA, "albano.json"))
    parts = inst0.parts
    opts = NestOptions(container=ContainerSpec.strip(inst0.strip_height), time_budget=0.5,
                       max_evaluations=8, seed=1, workers=1)
    lay = nest(parts, opts)
    inst, sep, shared = _exploring(lay, parts, opts)
    calls = []
    real = sep.separate

    def recording(X, Y, V, x1, *a, **k):
        best = shared.get()[0]
        start = colliding_total(sep.overlaps(X, Y, V), sep.eps)
        ok = real(X, Y, V, x1, *a, **k)
        calls.append(dict(x1=x1, best=best, ok=ok, start=start, end=(X.copy(), Y.copy(), V.copy())))
        if ok and len(calls) > 2 and all(not c["ok"] and c["best"] == best for c in calls[-3:-1]):
            sep.stop.set()                # the first success after two failures at one best
        return ok
    sep.separate = recording
    seed_rng(1)
    _explore(inst, sep, shared, time.monotonic() + 60.0, np.random.default_rng(1), [])
    pairs = list(zip(calls, calls[1:]))
    retries = [(a, b) for a, b in pairs if not a["ok"] and b["best"] == a["best"]]
    assert len(retries) >= 2 and retries[-1][1]["ok"], "no retry from the pool separated"
    assert all(b["x1"] == a["x1"] and b["start"] > 0.0 for a, b in retries)
    X, Y, V = retries[-1][1]["end"]
    x1, best = retries[-1][1]["x1"], retries[-1][1]["best"]
    assert inst.right_edge(X, V) <= x1 + 1e-6 < best
    new = inst.to_layout(lay, X, Y, V)
    fill_metrics(parts, new, opts)
    assert _valid(parts, new, opts) == []
    assert new.metrics["strip_length_mm"] < lay.metrics["strip_length_mm"]


def test_swap_of_a_large_and_a_small_copy_carries_the_covered_copies_into_the_room_left():
    """The exploration's disruption: a 40 x 40 copy and a 20 x 20 copy trade
    places; the two 10 x 10 copies next to the small one, which the large copy
    would now cover, move by the opposite shift into the room it leaves, so the
    swap creates no overlap (without that carry the large copy lands on both)."""
    parts = [rect("A", 40, 40), rect("B", 20, 20), rect("C", 10, 10, q=2)]
    opts = NestOptions(container=ContainerSpec.strip(40.0), time_budget=1.0, seed=1, workers=1,
                       rotations_override=[0])
    spots = [("A", 0, 0, 0), ("B", 0, 40, 0), ("C", 0, 40, 20), ("C", 1, 50, 20)]
    lay = Layout(containers=[Container(id="strip", kind="strip", outline=[])],
                 placements=[Placement(part_id=p, copy=k, container="strip", x=x, y=y, angle=0.0)
                             for p, k, x, y in spots])
    fill_metrics(parts, lay, opts)
    assert _valid(parts, lay, opts) == []
    inst = _Instance(lay, parts, opts)
    sep = Separator(PairTable(inst.variants), inst.cb, inst.choices, inst.types, inst.y0,
                    inst.y1, inst.x0, inst.eps, pad=inst.pad)
    X, Y, V = inst.X.copy(), inst.Y.copy(), inst.V.copy()
    _swap_large(inst, X, Y, V, np.random.default_rng(3))
    s = inst.scale
    assert (X[1] / s, Y[1] / s) == pytest.approx((10.0, 10.0), abs=0.01)    # B at A's centre
    assert (X[0] / s, Y[0] / s) == pytest.approx((30.0, -10.0), abs=0.01)   # A at B's centre
    # the C copies keep their places relative to A: shifted by A's move reversed
    assert np.allclose(np.c_[X[2:], Y[2:]] / s, [[10.0, 30.0], [20.0, 30.0]], atol=0.01)
    assert sep.overlaps(X, Y, V).max() <= inst.eps
    plain_x, plain_y = inst.X.copy(), inst.Y.copy()
    plain_x[[0, 1]], plain_y[[0, 1]] = X[[0, 1]], Y[[0, 1]]
    assert sep.overlaps(plain_x, plain_y, V).max() > 100 * inst.eps


def _kernel_args(tab, cb, pad):
    wmax = float((cb[:, 2] - cb[:, 0]).max())
    return pad + 2.0, wmax, *tab.costs(), 1.0, *tab.arrays()


def test_descent_steps_a_copy_out_of_an_overlap_to_the_free_side():
    """Coordinate descent (grown and halved steps on four axes): a 10 x 10 mm
    square 3 mm into another one in a 10 mm high strip can only get free by
    moving right; the descent from its place ends there, free of A."""
    from LeatherCutWorkbench.core.nesting.separation import _descend, seed_rng
    v = make_variants([piece_from_part(rect("s", 10, 10), 0.05, 90, [0])], 1000.0, 0.0, 0.05)
    tab = PairTable(v)
    core = np.asarray(v[0].core, dtype=np.float64)
    cb = np.array([core.min(axis=0).tolist() + core.max(axis=0).tolist()])
    contact = pair_depth(0.0, 0.0, 0, *tab.arrays())       # B this far right of A: touching
    X, Y, V, W = np.array([0.0, 7000.0]), np.zeros(2), np.zeros(2, dtype=np.int64), np.ones(2)
    y0, y1 = cb[0, 1], cb[0, 3]                              # no room up or down
    order = np.argsort(X + cb[V, 0])
    keys = (X + cb[V, 0])[order]
    pad, wmax, coff, cscale, ramp, *arrs = _kernel_args(tab, cb, 200.0)
    start = copy_penalty(1, 0, X[1], 0.0, X, Y, V, W, 1, 1e300, order, keys, -1e9, 1e9,
                         coff, cscale, ramp, *arrs)
    assert start > 1000.0
    seed_rng(3)
    x, y, c = _descend(1, 0, X[1], 0.0, start, X, Y, V, W, cb, 0.0, 40000.0, y0, y1, 1,
                       order, keys, pad, wmax, coff, cscale, ramp, *arrs, 0.25, 1e-4)
    assert c == 0.0 and y == 0.0
    assert contact - 1.0 <= x < 15000.0        # right of A, a few steps from where it was


def test_a_move_never_lands_on_a_costlier_place_and_stays_in_the_rectangle():
    """move_copy on fu's squeezed copies (real concave pieces, four rotations):
    a move ends inside the closed strip and costs less than where the copy
    was, or the copy stays (its place is one of the descents' starts)."""
    from LeatherCutWorkbench.core.nesting.separation import move_copy, seed_rng
    parts, opts = _fu()
    inst = _Instance(_loose_row(parts, opts, gap=1.0), parts, opts)
    tab = PairTable(inst.variants)
    X, Y, V = inst.X.copy(), inst.Y.copy(), inst.V.copy()
    x1 = inst.x0 + 0.6 * (inst.right_edge(X, V) - inst.x0)
    X[:] = np.minimum(X, x1 - inst.cb[V, 2])                   # pile the right end up
    W = np.ones((len(X), len(X)))
    pad, wmax, coff, cscale, ramp, *arrs = _kernel_args(tab, inst.cb, inst.pad)
    seed_rng(5)
    moved = 0
    for i in range(len(X)):
        order = np.argsort(X + inst.cb[V, 0])
        keys = (X + inst.cb[V, 0])[order]
        here = copy_penalty(i, V[i], X[i], Y[i], X, Y, V, W[i], tab.n, 1e300, order, keys,
                            -1e18, 1e18, coff, cscale, ramp, *arrs)
        ch = np.asarray(inst.choices[inst.types[i]], dtype=np.int64)
        x, y, v, c = move_copy(i, X, Y, V, W[i], ch, inst.cb, inst.x0, x1, inst.y0, inst.y1,
                               tab.n, 50, 25, pad, wmax, coff, cscale, ramp, *arrs)
        assert v in ch
        assert c <= here + 1e-9
        if c < here:                                           # moved: inside the closed strip
            b = inst.cb[v]
            assert inst.x0 - 1e-6 <= x + b[0] and x + b[2] <= x1 + 1e-6
            assert inst.y0 - 1e-6 <= y + b[1] and y + b[3] <= inst.y1 + 1e-6
            moved += 1
        else:
            assert (x, y, v) == (X[i], Y[i], V[i])             # nothing cheaper: stays
        X[i], Y[i], V[i] = x, y, v
    assert moved >= 3                                          # the piled-up copies got cheaper
