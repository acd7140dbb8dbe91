"""Overlap minimisation inside one hide: fit a copy the bottom-left fill left out.

The bottom-left fill packs Baldacci's large car-seat parts at 52-58 % per
hide; a set of hides that could hold every copy at ~60 % then keeps a copy
or two unplaced.  :class:`HideSeparator` takes the copies a hide holds plus
one more, lets them overlap and moves them until nothing overlaps and every
copy lies on the hide (sparrow's separation, Gardeyn et al. 2025, as the
strip engine does in :mod:`separation`; own implementation for an irregular
container).

Penalty of a layout: per pair of copies the penetration depth of their
relative translation in the pair's no-fit polygon (:mod:`overlap`; the
polygons are the bottom-left fill's own cached ones, ``Placer.nfps``), and
per copy a *container depth*: the distance from its reference point to the
inner-fit region of its variant in the hide (``Placer.hide_ifp``: where the
variant lies on usable material, defects and forbidden zones excluded) when
the point is outside it, 0 inside -- the shortest translation that puts the
copy back on the hide, the analogue of a penetration depth (computed as
the penetration depth in the region's complement, :class:`_Region`, by the
pair kernel itself).  Both are exact
for concave shapes and zero exactly when the copy is valid, so a layout of
total 0 is a layout the fill itself could have produced (every reference
point in its free region), within ``eps`` grid units.

The search is guided local search (the weights of pairs and copies that
stay in collision grow): each sweep moves every colliding copy to the
cheapest of candidate points of a random orientation of its part that fits
the hide (the vertices of its inner-fit region -- touching positions, where
the fill places -- and random points inside it), points near its place, and
a coordinate descent down to the contact tolerance.  Only the variants of the
part types in the hide are tabled, and their no-fit polygons come from the
fill's cache: on a Test2 hide (7 copies of 7 parts, 12 orientations each:
78 variants, 3,042 pairs) 2.5 s the first time, then mostly cached; the
inner-fit regions 0.3 s.  ``MAX_CHOICES`` = 4 orientations per placed copy
fitted fewer left-out copies than all 12 on Test2 states (measured).

Why numba: as in :mod:`overlap`, each candidate position is a loop over a
few hundred edges (the inner-fit region) and a few dozen per overlapping
pair, tens of thousands of candidates per second.  The kernels compile on
their first use after this file changed (~8 s, then loaded from numba's disk
cache in ~0.3 s; tools/setup.sh compiles them ahead, tools/warm_jit.py); the engine's parent ends its workers at the deadline
whatever they do, so the time budget holds even then.
"""

from __future__ import annotations

import time
from typing import Callable, Dict, List, Optional, Sequence, Tuple

import numpy as np
from numba import njit

from .overlap import (COST_OFFSET, PairTable, _edge_rows, copy_penalty, overlap_matrix,
                      pack_rings, pair_depth)
from .separation import Strikes, _clamp, colliding_total, reweigh, seed_rng

#: a copy in the hide: (type index, variant index, x, y), grid units
Copy = Tuple[int, int, int, int]

#: orientations a copy already on the hide may take (its own first, then
#: the others of its part, evenly spread); the copy to fit tries all
#: (12: every orientation of the benchmark's 30-degree steps, module doc)
MAX_CHOICES = 12
#: sweeps without a 0.1 % lower total before a strike, strikes before giving up
PATIENCE = 200
STRIKES = 3
#: candidate positions per move: uniform over the region, near the copy
N_GLOBAL = 40
N_LOCAL = 20
#: candidates tried for the first place of the copy to fit
N_INSERT = 1500
#: candidate points per variant (region vertices, as many inside it)
POOL = 200


@njit(cache=True, nogil=True, inline='always')
def container_depth(x: float, y: float, v: int, pts, start, count, ring_lo, ring_hi, bbox) -> float:
    """Container depth of variant ``v``'s reference point at (x, y): its
    penetration depth (:func:`overlap.pair_depth`) in the complement of the
    variant's inner-fit region (:class:`_Region`).  The complement ends at
    the far box, where ``pair_depth`` would say 0 -- a copy pushed out of
    the box (its region empty, or far from it: the complement's nearest edge
    is then the box) would count as on the hide.  Outside the box the depth
    is the box's width, deeper than anywhere inside it.  (A Baldacci Test6
    repair placed a copy at x = -7.6e11 grid units that way: the tail's
    checker then left it out.)"""
    if x <= bbox[v, 0] or x >= bbox[v, 2] or y <= bbox[v, 1] or y >= bbox[v, 3]:
        return bbox[v, 2] - bbox[v, 0]
    return pair_depth(x, y, v, pts, start, count, ring_lo, ring_hi, bbox)


@njit(cache=True, nogil=True)
def container_depths(X, Y, V, pts, start, count, ring_lo, ring_hi, bbox):
    """:func:`container_depth` of every copy, as an (n, 1) matrix."""
    n = X.shape[0]
    out = np.zeros((n, 1))
    for i in range(n):
        out[i, 0] = container_depth(X[i], Y[i], V[i], pts, start, count, ring_lo, ring_hi, bbox)
    return out


@njit(cache=True, nogil=True)
def _cost(i, v, x, y, X, Y, V, Wi, wc, nv, limit, order, keys, cb, wmax, coff, cscale, ramp,
          ccoff, cscale_c, cpts, cstart, ccount, clo, chi, cbox, pts, start, count, ring_lo, ring_hi,
          bbox) -> float:
    """Weighted penalty of copy ``i`` as variant ``v`` at (x, y): container
    depth (weight ``wc``) plus the pair overlaps (:func:`overlap.copy_penalty`,
    weights ``Wi``); stops early above ``limit``."""
    d = container_depth(x, y, v, cpts, cstart, ccount, clo, chi, cbox)
    c = 0.0
    if d > 0.0:
        off = ccoff[v] if d >= ramp else ccoff[v] * d / ramp
        c = wc * (d + off) * cscale_c[v]
        if c > limit:
            return c
    return c + copy_penalty(i, v, x, y, X, Y, V, Wi, nv, limit - c, order, keys,
                            x + cb[v, 0] - wmax - 2.0, x + cb[v, 2] + 2.0,
                            coff, cscale, ramp, pts, start, count, ring_lo, ring_hi, bbox)


@njit(cache=True, nogil=True)
def move_in_hide(i, X, Y, V, Wi, wc, choices, cb, ib, pool, pool_lo, nv, n_global, n_local, wmax, coff, cscale,
                 ramp, ccoff, cscale_c, cpts, cstart, ccount, clo, chi, cbox, pts, start, count,
                 ring_lo, ring_hi, bbox):
    """Best (x, y, variant, penalty) for copy ``i``: its place, ``n_global``
    points of a random choice's pool (``pool[pool_lo[v]:pool_lo[v + 1]]``:
    vertices of and points inside its inner-fit region), ``n_local`` near
    its place (clamped to the region's bounding box ``ib``), then a
    coordinate descent with a halving step (the strip's
    :func:`separation.move_copy` had this descent before it took three starts).
    ``cb``: outline boxes."""
    keys = X + cb[V, 0]
    order = np.argsort(keys)
    keys = keys[order]
    bv = V[i]
    bx = X[i]
    by = Y[i]
    best = _cost(i, bv, bx, by, X, Y, V, Wi, wc, nv, 1e300, order, keys, cb, wmax, coff, cscale,
                 ramp, ccoff, cscale_c, cpts, cstart, ccount, clo, chi, cbox, pts, start, count,
                 ring_lo, ring_hi, bbox)
    if best <= 0.0:
        return bx, by, bv, best
    nc = choices.shape[0]
    for s in range(n_global + n_local):
        if s < n_global:
            v = choices[np.random.randint(nc)]
            m = pool_lo[v + 1] - pool_lo[v]
            if m == 0:
                continue
            k = pool_lo[v] + np.random.randint(m)
            x = pool[k, 0]
            y = pool[k, 1]
        else:
            v = V[i] if np.random.random() < 0.8 else choices[np.random.randint(nc)]
            r = 0.3 if s % 2 == 0 else 0.05
            w = cb[v, 2] - cb[v, 0]
            h = cb[v, 3] - cb[v, 1]
            x = _clamp(X[i] + (np.random.random() - 0.5) * 2.0 * r * w, ib[v, 0], ib[v, 2])
            y = _clamp(Y[i] + (np.random.random() - 0.5) * 2.0 * r * h, ib[v, 1], ib[v, 3])
        c = _cost(i, v, x, y, X, Y, V, Wi, wc, nv, best, order, keys, cb, wmax, coff, cscale,
                  ramp, ccoff, cscale_c, cpts, cstart, ccount, clo, chi, cbox, pts, start, count,
                  ring_lo, ring_hi, bbox)
        if c < best:
            best, bx, by, bv = c, x, y, v
            if best <= 0.0:
                return bx, by, bv, best
    w = cb[bv, 2] - cb[bv, 0]
    h = cb[bv, 3] - cb[bv, 1]
    sx = 0.05 * w
    sy = 0.05 * h
    # The descent had :func:`separation.move_copy`'s shape but not its cost call
    # (container depth + pairs, no clamping to a rectangle) nor its floor; one
    # shared loop would take the cost as a function argument, and numba
    # (0.68, measured) does not disk-cache a kernel with a function argument:
    # it would recompile in every worker process, seconds of each budget.
    # down to the contact tolerance ``ramp``: dense hides need copies that touch
    floor = max(ramp, 1e-7 * max(w, h))
    while max(sx, sy) > floor and best > 0.0:
        improved = False
        for d in range(4):
            if d == 0:
                x, y = bx + sx, by
            elif d == 1:
                x, y = bx - sx, by
            elif d == 2:
                x, y = bx, by + sy
            else:
                x, y = bx, by - sy
            c = _cost(i, bv, x, y, X, Y, V, Wi, wc, nv, best, order, keys, cb, wmax, coff,
                      cscale, ramp, ccoff, cscale_c, cpts, cstart, ccount, clo, chi, cbox, pts, start,
                      count, ring_lo, ring_hi, bbox)
            if c < best:
                best, bx, by = c, x, y
                improved = True
                break
        if not improved:
            sx *= 0.5
            sy *= 0.5
    return bx, by, bv, best


@njit(cache=True, nogil=True)
def sweep_hide(hit, X, Y, V, W, WC, choice_lo, choice_flat, cb, ib, pool, pool_lo, nv, n_global, n_local, wmax,
               coff, cscale, ramp, ccoff, cscale_c, cpts, cstart, ccount, clo, chi, cbox, pts, start,
               count, ring_lo, ring_hi, bbox):
    """Move each copy of ``hit`` in turn; copy i may take the variants
    ``choice_flat[choice_lo[i]:choice_lo[i + 1]]``."""
    for i in hit:
        x, y, v, _ = move_in_hide(i, X, Y, V, W[i], WC[i, 0],
                                  choice_flat[choice_lo[i]:choice_lo[i + 1]], cb, ib, pool,
                                  pool_lo, nv,
                                  n_global, n_local, wmax, coff, cscale, ramp, ccoff, cscale_c,
                                  cpts, cstart, ccount, clo, chi, cbox, pts, start, count, ring_lo,
                                  ring_hi, bbox)
        X[i] = x
        Y[i] = y
        V[i] = v


def _bounds(rings: List[np.ndarray]) -> Tuple[float, float, float, float]:
    """Bounding box of ``rings`` (none: the empty box (0, 0, -1, -1))."""
    if not rings:
        return 0.0, 0.0, -1.0, -1.0
    p = np.vstack(rings)
    return p[:, 0].min(), p[:, 1].min(), p[:, 0].max(), p[:, 1].max()


class _Region:
    """The *complements* of the tabled variants' inner-fit regions in one hide,
    packed as :class:`overlap.PairTable` packs no-fit polygons (rings of
    variant v: ``ring_lo[v] .. ring_hi[v]``): a far box (CCW) around the
    region's rings reversed.  The container depth of a reference point is
    then its penetration depth in that complement, by the very kernel of the
    pair overlaps (0 inside the region).  ``ib``: the regions' bounding
    boxes (empty region: an empty box; its depth is the far box's distance)."""

    def __init__(self, rings: Sequence[List[np.ndarray]]):
        far = 1e4 * max([1.0] + [float(np.abs(r).max()) for rs in rings for r in rs])
        box = np.array([[-far, -far], [far, -far], [far, far], [-far, far]])
        self.pts, self.start, self.count, self.ring_lo, self.ring_hi, self.bbox = \
            pack_rings([[box] + [r[::-1] for r in rs] for rs in rings])
        self.ib = np.array([_bounds(rs) for rs in rings], dtype=np.float64).reshape(-1, 4)
        self.pool, self.pool_lo = self._pools(rings)

    def _pools(self, rings: Sequence[List[np.ndarray]], size: int = POOL):
        """Candidate points per variant: its region's vertices (touching
        positions, where the fill places; every k-th beyond ``size``) and
        as many random points inside it (rejection sampling in ``ib``)."""
        rng = np.random.default_rng(len(rings))
        out, lo = [], [0]
        for v, rs in enumerate(rings):
            pts = np.vstack(rs) if rs else np.zeros((0, 2))
            if len(pts) > size:
                pts = pts[::int(np.ceil(len(pts) / size))]
            if rs:
                x0, y0, x1, y1 = self.ib[v]
                cand = np.column_stack([rng.uniform(x0, x1, 8 * size), rng.uniform(y0, y1, 8 * size)])
                d = container_depths(cand[:, 0], cand[:, 1], np.full(len(cand), v, dtype=np.int64),
                                     *self.arrays())
                pts = np.vstack([pts, cand[d[:, 0] == 0.0][:size]])
            out.append(pts)
            lo.append(lo[-1] + len(pts))
        return np.ascontiguousarray(np.vstack(out)), np.asarray(lo, dtype=np.int64)

    def arrays(self):
        return self.pts, self.start, self.count, self.ring_lo, self.ring_hi, self.bbox


class HideSeparator:
    """Fits copies into a hide by overlap minimisation (module doc) on the
    bottom-left fill ``placer``'s geometry: its variants, cached no-fit
    polygons and inner-fit regions.  ``type_area``: part area per type
    (any unit: only ratios count); ``eps``: the depth (grid units) up to
    which a pair or a copy counts as touching, not colliding."""

    def __init__(self, placer, type_area: Sequence[float], eps: float):
        self.placer = placer
        self.type_area = type_area
        self.eps = eps
        self._ifp: Dict[Tuple[int, int], List[np.ndarray]] = {}
        #: seconds spent on no-fit polygons, inner-fit regions and separation
        self.table_s = 0.0
        self.separate_s = 0.0

    def _ifp_rings(self, hide: int, vi: int) -> List[np.ndarray]:
        """The fill's inner-fit region of variant ``vi`` on hide ``hide`` (its
        own outline against the defects, its convex hull against the hide
        outline: ``Placer.hide_ifp``).  The exact region of the part's own
        outline took 44 ms per variant against 4 ms on Test2 and fitted no
        more copies (measured twice)."""
        key = (hide, vi)
        hit = self._ifp.get(key)
        if hit is None:
            rings = [r for r in self.placer.hide_ifp(hide, vi) if len(r) >= 3]
            if not rings:
                # the hull fits nowhere, the outline may (a copy the fill placed with
                # ``Placer.concave_fit``): its exact region, else the copy could only leave
                rings = [r for r in self.placer.hide_ifp(hide, vi, concave=True) if len(r) >= 3]
            hit = self._ifp[key] = [np.asarray(r, dtype=np.float64) for r in rings]
        return hit

    def _choices(self, hide: int, t: int, current: Optional[int]) -> List[int]:
        """Variants of type ``t`` that fit the hide: all of them for the copy
        to fit (``current`` None), else ``current`` and up to ``MAX_CHOICES``
        - 1 others evenly spread over the part's orientations."""
        allv = list(self.placer.type_variants[t])
        if current is not None and len(allv) > MAX_CHOICES:
            k = allv.index(current) if current in allv else 0
            step = len(allv) / MAX_CHOICES
            allv = [allv[(k + int(round(j * step))) % len(allv)] for j in range(MAX_CHOICES)]
        return [v for v in allv if self._ifp_rings(hide, v)]

    def fit(self, hide: int, copies: Sequence[Copy], extra: Sequence[int], deadline: float,
            give_up: Optional[Callable[[], bool]] = None, seed: int = 0) -> Optional[List[Copy]]:
        """``copies`` (valid on hide ``hide``, a spec index of the placer) and
        one more copy of each type in ``extra``, all on the hide without
        overlap: the new layout (``copies`` in their order, then the extras)
        or None when the separation did not reach it by ``deadline``
        (``time.monotonic()``) or ``give_up()`` said so."""
        t0 = time.monotonic()
        types = [c[0] for c in copies] + list(extra)
        per_copy = [self._choices(hide, c[0], c[1]) for c in copies] + \
            [self._choices(hide, t, None) for t in extra]
        if any(not ch for ch in per_copy[len(copies):]):
            return None                          # a part that fits the hide nowhere
        for c, ch in zip(copies, per_copy):
            if c[1] not in ch:
                ch.insert(0, c[1])
        local = sorted({v for ch in per_copy for v in ch})
        at = {v: k for k, v in enumerate(local)}
        variants = self.placer.variants
        nfps = self.placer.nfps
        table = PairTable([variants[v] for v in local], deadline,
                          pair_rings=lambda a, b: nfps.get(local[a], local[b])[0])
        region = _Region([self._ifp_rings(hide, v) for v in local])
        self.table_s += time.monotonic() - t0
        if not table.complete or time.monotonic() > deadline:
            return None
        n = len(types)
        X = np.zeros(n)
        Y = np.zeros(n)
        V = np.zeros(n, dtype=np.int64)
        for i, c in enumerate(copies):
            X[i], Y[i], V[i] = c[2], c[3], at[c[1]]
        ch_local = [np.asarray([at[v] for v in ch], dtype=np.int64) for ch in per_copy]
        choice_lo = np.cumsum([0] + [len(c) for c in ch_local]).astype(np.int64)
        choice_flat = np.concatenate(ch_local).astype(np.int64)
        cb = np.array([variants[v].bbox for v in local], dtype=np.float64)
        area = np.array([float(self.type_area[variants[v].type_index]) for v in local])
        diam = np.hypot(cb[:, 2] - cb[:, 0], cb[:, 3] - cb[:, 1])
        size = np.sqrt(np.sqrt(np.outer(area, area))).mean()
        kern = _Kernels(table, region, cb, choice_lo, choice_flat,
                        COST_OFFSET * diam, np.sqrt(area) / max(size, 1e-300), self.eps)
        seed_rng(seed)
        W = np.ones((n, n))
        WC = np.ones((n, 1))
        for i in range(len(copies), n):          # the extras: their least-penalty place first
            ib = region.ib[ch_local[i][0]]
            V[i] = ch_local[i][0]
            X[i], Y[i] = 0.5 * (ib[0] + ib[2]), 0.5 * (ib[1] + ib[3])
            kern.sweep(np.array([i], dtype=np.int64), X[:i + 1], Y[:i + 1], V[:i + 1],
                       W, WC, N_INSERT, N_LOCAL)
        ok = self._separate(kern, X, Y, V, W, WC, deadline, give_up,
                            np.random.default_rng(seed))
        self.separate_s += time.monotonic() - t0
        if not ok:
            return None
        X, Y = np.round(X), np.round(Y)
        if kern.total(X, Y, V) > 0.0:            # rounding to the grid pushed a copy in
            return None
        return [(types[i], local[int(V[i])], int(X[i]), int(Y[i])) for i in range(n)]

    def _separate(self, kern: "_Kernels", X, Y, V, W, WC, deadline: float,
                  give_up: Optional[Callable[[], bool]], rng) -> bool:
        """Guided local search until nothing collides (True; X, Y, V hold the
        layout) or ``PATIENCE`` x ``STRIKES`` sweeps without progress, the
        deadline or ``give_up()`` (False)."""
        eps = self.eps
        od, cd = kern.measure(X, Y, V)
        total = colliding_total(od, eps) + colliding_total(cd, eps)
        if total == 0.0:
            return True
        track = Strikes(total, X, Y, V, PATIENCE, STRIKES)
        while time.monotonic() < deadline and not (give_up is not None and give_up()):
            hit = np.nonzero((od > eps).any(axis=1) | (cd[:, 0] > eps))[0]
            rng.shuffle(hit)
            kern.sweep(hit, X, Y, V, W, WC, N_GLOBAL, N_LOCAL)
            od, cd = kern.measure(X, Y, V)
            total = colliding_total(od, eps) + colliding_total(cd, eps)
            if total == 0.0:
                return True
            reweigh(od, W, eps)
            reweigh(cd, WC, eps)
            step = track.after_sweep(total, X, Y, V)
            if step == "stop":
                break
            if step == "reset":
                od, cd = kern.measure(X, Y, V)
        return False


class _Kernels:
    """The arrays of one separation, bound to the kernels."""

    def __init__(self, table: PairTable, region: _Region, cb, choice_lo, choice_flat,
                 ccoff, cscale_c, eps: float):
        self.table, self.region = table, region
        self.cb, self.choice_lo, self.choice_flat = cb, choice_lo, choice_flat
        self.ccoff, self.cscale_c, self.eps = ccoff, cscale_c, eps
        self.ib = region.ib
        self.wmax = float((cb[:, 2] - cb[:, 0]).max())

    def sweep(self, hit, X, Y, V, W, WC, n_global: int, n_local: int) -> None:
        sweep_hide(hit, X, Y, V, W, WC, self.choice_lo, self.choice_flat, self.cb, self.ib,
                   self.region.pool, self.region.pool_lo, self.table.n, n_global, n_local, self.wmax, *self.table.costs(), self.eps,
                   self.ccoff, self.cscale_c, *self.region.arrays(), *self.table.arrays())

    def measure(self, X, Y, V):
        """(pair depths n x n, container depths n x 1), unweighted."""
        return (overlap_matrix(X, Y, V, self.table.n, *self.table.arrays()),
                container_depths(X, Y, V, *self.region.arrays()))

    def total(self, X, Y, V) -> float:
        od, cd = self.measure(X, Y, V)
        return colliding_total(od, self.eps) + colliding_total(cd, self.eps)


def warm_up() -> None:
    """Compile (or load from numba's disk cache) the kernels on a one-copy
    hide: called at set-up by tools/warm_jit.py."""
    sq = np.array([[0.0, 0.0], [10.0, 0.0], [10.0, 10.0], [0.0, 10.0]])
    region = _Region([[sq]])
    X, Y = np.zeros(1), np.zeros(1)
    V = np.zeros(1, dtype=np.int64)
    container_depths(X, Y, V, *region.arrays())
    pts = _edge_rows([-sq])
    bbox = np.array([[-10.0, -10.0, 0.0, 0.0]])
    one = np.zeros(1, dtype=np.int64)
    sweep_hide(one, X, Y, V, np.ones((1, 1)), np.ones((1, 1)), np.array([0, 1], dtype=np.int64),
               one, np.array([[0.0, 0.0, 10.0, 10.0]]), region.ib, region.pool, region.pool_lo,
               1, 1, 1, 10.0,
               np.zeros(1), np.ones(1), 1.0, np.zeros(1), np.ones(1), *region.arrays(),
               pts, one, np.array([4], dtype=np.int64), one, np.ones(1, dtype=np.int64), bbox)
    overlap_matrix(X, Y, V, 1, pts, one, np.array([4], dtype=np.int64), one,
                   np.ones(1, dtype=np.int64), bbox)
    reweigh(np.zeros((1, 1)), np.ones((1, 1)), 0.0)
    colliding_total(np.zeros((1, 1)), 0.0)
