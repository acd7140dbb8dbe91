"""The time budget and the anytime behaviour of the own engine: exact no-fit
polygons from convex pieces, coarse (convex-hull) ones under time pressure,
abandoned evaluations at the deadline, Stop keeps the best layout, on_best
sees every improvement."""

import math
import time

import pyclipper
from shapely.geometry import Polygon

from LeatherCutWorkbench.core.nesting import ContainerSpec, NestOptions, check_layout, nest
from LeatherCutWorkbench.core.nesting.blf import BinSpec, Placer
from LeatherCutWorkbench.core.nesting.convex import convex_pieces
from LeatherCutWorkbench.core.nesting.nfp import Clock, NfpCache, _neg, _shift, union
from LeatherCutWorkbench.core.nesting.shapes import make_variants, piece_from_part

from nest_shapes import disc, l_shape, rect, ring


def _variants(parts, spacing=2.0, scale=1000.0):
    types = [piece_from_part(p, 0.05, 90.0, [0.0, 90.0]) for p in parts]
    return make_variants(types, scale, spacing / 2.0, 0.05)


def _sweep_nfp(a, b):
    """The plain pyclipper sweep (the engine's former method) as the reference."""
    nb = _neg(b)
    s = pyclipper.MinkowskiSum(nb, a, True)
    outers = [p for p in union(list(s) + [_shift(a, nb[0][0], nb[0][1]), _shift(nb, a[0][0], a[0][1])])
              if pyclipper.Orientation(p)]
    return max(outers, key=pyclipper.Area)


def test_convex_pieces_tile_the_ring_and_nfps_match_the_sweep():
    vs = _variants([l_shape("L", 60, 40, 12), ring("R", 30, 18), disc("d", 9)])
    for v in vs:
        pieces = convex_pieces(v.outer)
        assert pieces
        assert abs(sum(abs(pyclipper.Area(p)) for p in pieces) - abs(pyclipper.Area(v.outer))) < 1.0
    cache = NfpCache(vs)
    for a in range(len(vs)):
        for b in range(len(vs)):
            got = Polygon(cache.get(a, b)[0][0].tolist())
            ref = Polygon(_sweep_nfp(vs[a].outer, vs[b].outer))
            assert got.symmetric_difference(ref).area <= 1e-6 * ref.area + 10.0


def test_coarse_nfps_after_the_exact_deadline_contain_the_exact_ones():
    vs = _variants([l_shape("L", 60, 40, 12), disc("d", 9)])
    exact = NfpCache(vs)
    coarse = NfpCache(vs, Clock(exact_until=time.monotonic() - 1.0))
    for a in range(len(vs)):
        for b in range(len(vs)):
            e = Polygon(exact.get(a, b)[0][0].tolist())
            c = Polygon(coarse.get(a, b)[0][0].tolist())
            assert c.buffer(1.0).contains(e)        # superset: a coarse layout stays valid
            assert c.area >= e.area


def test_evaluations_are_abandoned_at_the_deadline_and_the_first_fill_hard_stop():
    vs = _variants([rect("a", 20, 10)])
    tv = [[v.index for v in vs]]
    clock = Clock(stop_at=time.monotonic() - 1.0)
    placer = Placer(vs, tv, [0], [BinSpec("sheet", (0, 0, 100000, 100000))], True, None, clock=clock)
    seq = [(0, None)] * 3
    assert placer.place(seq) is None                     # abandoned: out of time
    clock.hard_stop = time.monotonic() - 1.0
    tr = placer.place(seq, abortable=False)              # the first fill goes on, boxes only
    assert tr is not None and tr.unplaced == []
    clock.give_up_at = time.monotonic() - 1.0
    assert placer.place(seq, abortable=False).unplaced == [0, 1, 2]     # last resort
    clock.hard_stop = clock.give_up_at = math.inf
    assert placer.place(seq, abortable=False).unplaced == []


def test_stop_keeps_the_best_layout_and_on_best_sees_it():
    parts = [l_shape("L", 60, 40, 12, q=6), disc("d", 9, q=8), rect("r", 30, 20, q=6)]
    seen = []
    opts = NestOptions(container=ContainerSpec.sheet(200, 150), spacing=1, time_budget=120,
                       workers=1)
    t0 = time.monotonic()
    lay = nest(parts, opts, on_best=seen.append, stop=lambda: len(seen) >= 1)
    assert time.monotonic() - t0 < 60                  # Stop ended a 120 s search
    assert lay.metrics["stopped"] is True
    assert seen and seen[0].placements
    assert check_layout(parts, lay, spacing=1) == []
    assert lay.unplaced == []
