"""Overlap minimisation ("separation") of copies in a rectangle.

Given copies at positions that may overlap, move them until no pair
overlaps, or give up.  The overlap of a pair is its penetration depth
(:mod:`overlap`); the search minimises the *weighted* sum of the depths with
guided local search: after every sweep the weight of each pair that still
overlaps grows, the others decay back towards 1, so a stubborn collision
becomes expensive and the copies around it move aside instead of the search
cycling between the same few arrangements (the idea of Egeblad et al. 2007
and of sparrow, Gardeyn et al. 2025; own implementation).

One move takes one overlapping copy out and puts it back at the cheapest of
a set of candidates: uniform samples over the whole rectangle in every
allowed orientation, samples near its current place, then a coordinate
descent (four axes, a step that grows on success and halves on failure) from
each of the three cheapest distinct ones (as sparrow's sampler does).  The
copy never lands somewhere worse than where it was (its current place is a
candidate).

All lengths are grid units of the engine (:mod:`shapes`).  The rectangle
constrains each copy's *core* bounding box (true outline + chord error +
one unit): a copy inside it lies inside the container.
"""

from __future__ import annotations

import threading
import time
from typing import Callable, Optional

import numpy as np
from numba import njit

from .overlap import PairTable, copy_penalty, overlap_matrix



#: sweeps without a 0.1 % lower total overlap before a strike (back to the
#: least-overlapping layout of this separation), and strikes before giving up;
#: measured on albano and shirts (40 s phase, 3 seeds): 200 x 2 and 100 x 3
#: both reach shorter strips than 50 x 5 (fewer, later give-ups)
PATIENCE = 200
STRIKES = 2
#: a move descends from this many of its cheapest distinct candidates
#: (:func:`move_copy`; distinct: farther apart than ``UNIQUE`` x the smaller
#: side of the copy's core box, or another variant); measured on fixed starts
#: (shirts at 86.75 %, the strip 0.1 % shorter, 16 tries each): one descent
#: with a halving step separated 1 of 16, three of these descents 7-8 of 16
N_STARTS = 3
UNIQUE = 0.05
#: coordinate descent steps (:func:`_descend`): first and last step as a share of
#: the core box's smaller side, growth after a better step, shrink after none.
#: The starts descend down to ``CD_COARSE``, only the best of them on to
#: ``CD_LAST`` (fixed starts: shirts 0.05 % shorter 9/16 -> 11/16 separations
#: at half the CPU time, albano 0.12 % shorter the same 2/16 at 0.8x)
CD_FIRST = 0.25
CD_COARSE = 0.01
CD_LAST = 1e-4
CD_GROW = 1.1
CD_SHRINK = 0.5


@njit(cache=True)
def seed_rng(seed: int) -> None:
    """Seed numba's own random stream (one per process)."""
    np.random.seed(seed)


@njit(cache=True)
def _clamp(v: float, lo: float, hi: float) -> float:
    if v < lo:
        return lo
    if v > hi:
        return hi
    return v


@njit(cache=True, nogil=True, inline='always')
def _cost(i, v, x, y, X, Y, V, W, cb, nv, limit, order, keys, pad, wmax, coff, cscale, ramp,
          pts, start, count, ring_lo, ring_hi, bbox) -> float:
    """:func:`copy_penalty` of copy ``i`` as variant ``v`` at (x, y), with the
    broad-phase window of copies whose left edge can reach it."""
    return copy_penalty(i, v, x, y, X, Y, V, W, nv, limit, order, keys,
                        x + cb[v, 0] - wmax - 2 * pad, x + cb[v, 2] + 2 * pad,
                        coff, cscale, ramp, pts, start, count, ring_lo, ring_hi, bbox)


@njit(cache=True, nogil=True)
def _descend(i, bv, bx, by, best, X, Y, V, W, cb, x0, x1, y0, y1, nv, order, keys, pad, wmax,
             coff, cscale, ramp, pts, start, count, ring_lo, ring_hi, bbox, first, last):
    """Coordinate descent of copy ``i`` (variant ``bv``) from (bx, by) with cost
    ``best``: two opposite steps along one axis of four (x, y, both diagonals),
    starting at a random one; the better of them, if better than the current
    place, is taken and that axis's step grows x ``CD_GROW``, else it shrinks
    x ``CD_SHRINK`` and the next axis follows (a diagonal scales both steps by
    the square root).  Steps run from ``first`` down to ``last`` of the core
    box's smaller side (the step rule of sparrow's coordinate descent,
    Gardeyn et al. 2025; own code).  Returns (x, y, cost)."""
    lx, hx = x0 - cb[bv, 0], x1 - cb[bv, 2]
    ly, hy = y0 - cb[bv, 1], y1 - cb[bv, 3]
    side = min(cb[bv, 2] - cb[bv, 0], cb[bv, 3] - cb[bv, 1])
    sx = sy = first * side
    floor = last * side
    axis = np.random.randint(4)
    while (sx >= floor or sy >= floor) and best > 0.0:
        ax = 0.0 if axis == 1 else (sx if axis != 3 else -sx)
        ay = 0.0 if axis == 0 else sy
        improved = False
        nx, ny = bx, by
        for sgn in (1.0, -1.0):
            x = _clamp(bx + sgn * ax, lx, hx)
            y = _clamp(by + sgn * ay, ly, hy)
            c = _cost(i, bv, x, y, X, Y, V, W, cb, nv, best, order, keys, pad, wmax, coff,
                      cscale, ramp, pts, start, count, ring_lo, ring_hi, bbox)
            if c < best:
                best, nx, ny = c, x, y
                improved = True
        bx, by = nx, ny
        k = CD_GROW if improved else CD_SHRINK
        if axis == 0:
            sx *= k
        elif axis == 1:
            sy *= k
        else:
            k = np.sqrt(k)
            sx *= k
            sy *= k
        if not improved:
            axis = (axis + 1) % 4
    return bx, by, best


@njit(cache=True, nogil=True)
def move_copy(i, X, Y, V, W, choices, cb, x0, x1, y0, y1, nv, n_global, n_local, pad, wmax,
              coff, cscale, ramp, pts, start, count, ring_lo, ring_hi, bbox):
    """Best place for copy ``i`` (see module doc): (x, y, variant, weighted
    penalty).  ``choices`` are the variants its type allows, ``cb`` the core
    bounding boxes per variant, (x0, y0)-(x1, y1) the rectangle; ``pad``
    bounds how far an inflated outline reaches beyond its core box, ``wmax``
    the widest core box (both for the broad phase).  The ``N_STARTS``
    cheapest distinct candidates (its current place among them) each start a
    coarse coordinate descent (:func:`_descend`); the cheapest result is
    refined with finer steps and wins."""
    keys = X + cb[V, 0]
    order = np.argsort(keys)
    keys = keys[order]
    bv = V[i]
    c = _cost(i, bv, X[i], Y[i], X, Y, V, W, cb, nv, 1e300, order, keys, pad, wmax, coff,
              cscale, ramp, pts, start, count, ring_lo, ring_hi, bbox)
    if c <= 0.0:
        return X[i], Y[i], bv, c
    # the kept candidates: cost (1e300 = empty slot), place, variant
    sc = np.full(N_STARTS, 1e300)
    sx = np.zeros(N_STARTS)
    sy = np.zeros(N_STARTS)
    sv = np.zeros(N_STARTS, dtype=np.int64)
    sc[0], sx[0], sy[0], sv[0] = c, X[i], Y[i], bv
    nc = choices.shape[0]
    w = cb[bv, 2] - cb[bv, 0]
    h = cb[bv, 3] - cb[bv, 1]
    near = UNIQUE * min(w, h)
    for s in range(n_global + n_local):
        if s < n_global:
            v = choices[np.random.randint(nc)]
            lx, hx = x0 - cb[v, 0], x1 - cb[v, 2]
            ly, hy = y0 - cb[v, 1], y1 - cb[v, 3]
            if hx < lx or hy < ly:
                continue
            x = lx + np.random.random() * (hx - lx)
            y = ly + np.random.random() * (hy - ly)
        else:
            v = V[i] if np.random.random() < 0.8 else choices[np.random.randint(nc)]
            lx, hx = x0 - cb[v, 0], x1 - cb[v, 2]
            ly, hy = y0 - cb[v, 1], y1 - cb[v, 3]
            if hx < lx or hy < ly:
                continue
            r = 0.5 if s % 2 == 0 else 0.1
            x = _clamp(X[i] + (np.random.random() - 0.5) * 2.0 * r * w, lx, hx)
            y = _clamp(Y[i] + (np.random.random() - 0.5) * 2.0 * r * h, ly, hy)
        worst = np.argmax(sc)
        c = _cost(i, v, x, y, X, Y, V, W, cb, nv, sc[worst], order, keys, pad, wmax, coff,
                  cscale, ramp, pts, start, count, ring_lo, ring_hi, bbox)
        if c >= sc[worst]:
            continue
        if c <= 0.0:
            return x, y, v, c
        # a candidate close to a kept one of the same variant replaces it (if
        # cheaper), so the descents start from different places
        slot = worst
        for k in range(N_STARTS):
            if sc[k] < 1e300 and sv[k] == v and abs(sx[k] - x) < near and abs(sy[k] - y) < near:
                slot = k
                break
        if c < sc[slot]:
            sc[slot], sx[slot], sy[slot], sv[slot] = c, x, y, v
    best, bx, by, bv = 1e300, X[i], Y[i], V[i]
    for k in np.argsort(sc):
        if sc[k] >= 1e300:
            break
        x, y, c = _descend(i, sv[k], sx[k], sy[k], sc[k], X, Y, V, W, cb, x0, x1, y0, y1, nv,
                           order, keys, pad, wmax, coff, cscale, ramp, pts, start, count,
                           ring_lo, ring_hi, bbox, CD_FIRST, CD_COARSE)
        if c < best:
            best, bx, by, bv = c, x, y, sv[k]
            if best <= 0.0:
                return bx, by, bv, best
    bx, by, best = _descend(i, bv, bx, by, best, X, Y, V, W, cb, x0, x1, y0, y1, nv,
                            order, keys, pad, wmax, coff, cscale, ramp, pts, start, count,
                            ring_lo, ring_hi, bbox, 2.0 * CD_COARSE, CD_LAST)
    return bx, by, bv, best


@njit(cache=True, nogil=True)
def sweep(hit, X, Y, V, W, types, choice_lo, choice_flat, cb, x0, x1, y0, y1, nv, n_global,
          n_local, pad, wmax, coff, cscale, ramp, pts, start, count, ring_lo, ring_hi, bbox):
    """Move each copy of ``hit`` in turn (:func:`move_copy`); copy i's type t
    allows the variants ``choice_flat[choice_lo[t]:choice_lo[t + 1]]``.  One
    compiled loop: per move from Python the call alone cost ~10 % of a move."""
    for i in hit:
        t = types[i]
        x, y, v, _ = move_copy(i, X, Y, V, W[i], choice_flat[choice_lo[t]:choice_lo[t + 1]], cb,
                               x0, x1, y0, y1, nv, n_global, n_local, pad, wmax, coff, cscale,
                               ramp, pts, start, count, ring_lo, ring_hi, bbox)
        X[i] = x
        Y[i] = y
        V[i] = v


@njit(cache=True, nogil=True)
def colliding_total(od, eps: float) -> float:
    """Sum of the depths above ``eps`` (both triangles of the matrix)."""
    total = 0.0
    for i in range(od.shape[0]):
        for j in range(od.shape[1]):
            if od[i, j] > eps:
                total += od[i, j]
    return total


class Strikes:
    """The least-colliding layout of one guided local search and its give-up
    rule: a sweep that lowers the best total overlap by less than 0.1 % is
    stale; after ``patience`` stale sweeps in a row the search strikes and
    goes back to the best layout, and after ``strikes`` strikes it gives up."""

    def __init__(self, total: float, X, Y, V, patience: int, strikes: int):
        self.best = (total, X.copy(), Y.copy(), V.copy())
        self.patience = patience
        self.strikes = strikes
        self._stale = 0
        self._strike = 0

    def after_sweep(self, total: float, X, Y, V) -> str:
        """``"on"``: search on; ``"reset"``: X, Y, V now hold the best layout
        again (their overlaps must be measured anew); ``"stop"``: give up."""
        if total < self.best[0] * 0.999:
            self.best = (total, X.copy(), Y.copy(), V.copy())
            self._stale = 0
            return "on"
        self._stale += 1
        if self._stale < self.patience:
            return "on"
        self._strike += 1
        self._stale = 0
        if self._strike >= self.strikes:
            return "stop"
        self.restore(X, Y, V)
        return "reset"

    def restore(self, X, Y, V) -> None:
        """Put the best layout seen into X, Y, V."""
        X[:], Y[:], V[:] = self.best[1], self.best[2], self.best[3]


@njit(cache=True, nogil=True)
def reweigh(od, W, eps: float) -> None:
    """Guided local search: the weight of a colliding pair grows (x1.2 for the
    slightest overlap up to x2 for the deepest one, at most 1e6), the others
    decay back to 1 (x0.95)."""
    top = od.max()
    for i in range(od.shape[0]):
        for j in range(od.shape[1]):
            if od[i, j] > eps:
                W[i, j] = min(W[i, j] * (1.2 + 0.8 * od[i, j] / top), 1e6)
            else:
                W[i, j] = max(1.0, W[i, j] * 0.95)


class Separator:
    """Guided local search that removes the overlaps of copies in a rectangle.

    ``V`` (variant per copy), ``X`` / ``Y`` (reference point per copy) are
    changed in place; ``choices[t]`` lists the variants of type t, ``types[i]``
    the type of copy i, ``cb`` the core bounding boxes per variant.  A pair
    overlaps when its penetration depth exceeds ``eps`` grid units (the
    caller keeps that far below the checker's tolerance); ``pad`` bounds how
    far a variant's inflated outline reaches beyond its core box."""

    def __init__(self, table: PairTable, cb: np.ndarray, choices, types: np.ndarray,
                 y0: float, y1: float, x0: float, eps: float, n_global: int = 50,
                 n_local: int = 25, stop: Optional[threading.Event] = None,
                 pad: float = 0.0):
        self.table = table
        self.arrs = table.arrays()
        self.cb = cb
        self.choices = [np.asarray(c, dtype=np.int64) for c in choices]
        self.choice_lo = np.cumsum([0] + [len(c) for c in self.choices]).astype(np.int64)
        self.choice_flat = np.concatenate(self.choices).astype(np.int64)
        self.types = types
        self.x0, self.y0, self.y1 = x0, y0, y1
        self.n_global, self.n_local = n_global, n_local
        self.eps = eps
        self.pad = pad + 2.0
        self.wmax = float((cb[:, 2] - cb[:, 0]).max())
        self.stop = stop or threading.Event()      # set: give up at the next sweep
        n = len(types)
        self.W = np.ones((n, n))

    def warm_up(self, X, Y, V, x1: float) -> None:
        """Compile (or load from numba's disk cache) every kernel once."""
        seed_rng(0)
        self.overlaps(X, Y, V)
        self._sweep(np.zeros(1, dtype=np.int64), X.copy(), Y.copy(), V.copy(), x1, 1, 1)
        od = self.overlaps(X, Y, V)
        colliding_total(od, self.eps)
        reweigh(od, np.ones_like(od), self.eps)

    def _sweep(self, hit, X, Y, V, x1, n_global, n_local) -> None:
        sweep(hit, X, Y, V, self.W, self.types, self.choice_lo, self.choice_flat, self.cb,
              self.x0, x1, self.y0, self.y1, self.table.n, n_global, n_local, self.pad,
              self.wmax, *self.table.costs(), self.eps, *self.arrs)

    def overlaps(self, X, Y, V) -> np.ndarray:
        return overlap_matrix(X, Y, V, self.table.n, *self.arrs)

    def separate(self, X, Y, V, x1: float, deadline: float, patience: int = PATIENCE,
                 strikes: int = STRIKES, rng: Optional[np.random.Generator] = None,
                 give_up: Optional[Callable[[], bool]] = None) -> bool:
        """Remove every overlap with the rectangle closed at ``x1``; True on
        success (X, Y, V then hold the overlap-free layout).  On failure they
        hold the least-overlapping layout seen.  ``give_up()`` is asked after
        every sweep: True ends the separation as a failure (e.g. another worker
        already reached ``x1``)."""
        rng = rng or np.random.default_rng(0)
        od = self.overlaps(X, Y, V)
        total = colliding_total(od, self.eps)
        if total == 0.0:
            return True
        track = Strikes(total, X, Y, V, patience, strikes)
        while time.monotonic() < deadline and not self.stop.is_set():
            hit = np.nonzero((od > self.eps).any(axis=1))[0]
            rng.shuffle(hit)
            self._sweep(hit, X, Y, V, x1, self.n_global, self.n_local)
            od = self.overlaps(X, Y, V)
            total = colliding_total(od, self.eps)
            if total == 0.0:
                return True
            if give_up is not None and give_up():
                break
            reweigh(od, self.W, self.eps)
            step = track.after_sweep(total, X, Y, V)
            if step == "stop":
                break
            if step == "reset":
                od = self.overlaps(X, Y, V)
        track.restore(X, Y, V)
        return False
