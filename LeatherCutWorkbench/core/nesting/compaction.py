"""Left compaction of an overlap-free strip layout.

At the end of the strip phase (:mod:`strip_shrink`) the kept overlap-free
layouts often still leave gaps: the separator (:mod:`separation`) stops at
the first overlap-free arrangement, so a copy may float a little right of
where it could lie.  :func:`compact_left` moves each copy, leftmost first,
as far left as it can go without a new overlap: jumps that halve from the
whole distance to the strip's start down to a small floor, straight left or
diagonally (left and down, left and up, so a copy resting on a neighbour's
slope can slide past it).  The strip's right edge can only move left.

Invariant: no pair's penetration depth (:func:`overlap.pair_depth`) exceeds
``eps`` after a move that did not exceed it before (the separator's own
overlap test); every copy's core box stays inside the strip's rows and right
of its start.  Lengths are grid units of the engine (:mod:`shapes`).

Why numba: one compaction tests a few thousand candidate places against
every other copy (a bounding-box reject, then the edges of one no-fit
polygon); in plain Python that is ~100x slower.  Hand-written: no library
moves copies against packed no-fit polygons.
"""

from __future__ import annotations

import numpy as np
from numba import njit

from .overlap import pair_depth

#: the smallest jump, as a share of the copy's smaller core-box side
FLOOR_SHARE = 1e-4
#: passes over all copies at most (a pass that moves nothing ends early)
PASSES = 3


@njit(cache=True, nogil=True)
def _clear(i, v, x, y, X, Y, V, nv, eps, pts, start, count, ring_lo, ring_hi, bbox) -> bool:
    """Does copy ``i`` as variant ``v`` at (x, y) overlap no other copy by
    more than ``eps``?"""
    for j in range(X.shape[0]):
        if j == i:
            continue
        p = v * nv + V[j]
        tx = X[j] - x
        ty = Y[j] - y
        # the box test inline, as in overlap's cost loop (a shared helper would
        # be a call per pair in both hot loops: measured 10x the test there)
        if tx <= bbox[p, 0] or tx >= bbox[p, 2] or ty <= bbox[p, 1] or ty >= bbox[p, 3]:
            continue
        if pair_depth(tx, ty, p, pts, start, count, ring_lo, ring_hi, bbox) > eps:
            return False
    return True


@njit(cache=True, nogil=True)
def compact_left(X, Y, V, cb, x0: float, y0: float, y1: float, eps: float, nv: int,
                 pts, start, count, ring_lo, ring_hi, bbox) -> float:
    """Move every copy of the overlap-free layout (X, Y, V) left as far as it
    goes (see module doc); X and Y change in place.  ``cb`` holds the core
    boxes per variant, ``x0`` the strip's start, ``y0``/``y1`` its rows.
    Returns the total distance moved (grid units)."""
    n = X.shape[0]
    moved = 0.0
    for _ in range(PASSES):
        pass_moved = 0.0
        order = np.argsort(X + cb[V, 0])
        for k in range(n):
            i = order[k]
            v = V[i]
            lx = x0 - cb[v, 0]
            ly, hy = y0 - cb[v, 1], y1 - cb[v, 3]
            side = min(cb[v, 2] - cb[v, 0], cb[v, 3] - cb[v, 1])
            floor = FLOOR_SHARE * side
            step = X[i] - lx
            while step >= floor:
                done = False
                for d in range(3):            # left, left-down, left-up
                    x = X[i] - step
                    y = Y[i] if d == 0 else (Y[i] - step if d == 1 else Y[i] + step)
                    if x < lx or y < ly or y > hy:
                        continue
                    if _clear(i, v, x, y, X, Y, V, nv, eps, pts, start, count,
                              ring_lo, ring_hi, bbox):
                        pass_moved += X[i] - x
                        X[i] = x
                        Y[i] = y
                        done = True
                        break
                if done:
                    step = min(step, X[i] - lx)
                else:
                    step *= 0.5
        moved += pass_moved
        if pass_moved <= 0.0:
            break
    return moved
