"""Overlap penalty of translated piece variants, from their no-fit polygons.

For variants a (fixed at the origin) and b, ``NFP(a, b)`` is the set of
translations of b that make it overlap a (:func:`nfp.pair_nfp`, grid units).
For placed copies i (variant a at p_i) and j (variant b at p_j) the relative
translation t = p_j - p_i lies inside that polygon exactly when they overlap,
and the distance from t to the polygon's boundary is their *penetration
depth*: the shortest translation of j that separates them.  It is zero when
they touch, grows continuously with the overlap and is exact for concave
shapes -- the quantity Egeblad et al. (2007) and Imamichi et al. (2009)
minimise.  The separator (:mod:`separation`) minimises a weighted sum of a
cost built on it: an overlapping pair costs its depth plus ``COST_OFFSET`` x
the larger diameter, times a size factor (:func:`copy_penalty`); measured on
the ESICUP strips, this reached 1-2 % shorter strips than the depth alone,
because many shallow overlaps no longer look nearly as good as none.

:class:`PairTable` packs every variant pair's polygon rings into flat arrays
(ring offsets per pair, a bounding box per pair for a fail-fast reject).
The kernels below test one translation against one pair with a non-zero
winding number and a point-to-segment distance over the pair's edges.

Why numba: the separator evaluates millions of (candidate position, other
copy) pairs per second; each is a loop over a few dozen polygon edges with
an early bounding-box exit.  That loop does not vectorise well in numpy (the
edge counts differ per pair and most pairs exit after the box test), and in
plain Python it is ~100x slower.  The kernels are compiled once and cached
on disk (``cache=True``).
"""

from __future__ import annotations

import time
from typing import Callable, List, Optional, Sequence

import numpy as np
import pyclipper
from numba import njit

from .nfp import pair_nfp
from .shapes import Variant


#: an overlapping pair costs at least this share of the larger copy's diameter
#: (times its weight), so the search prefers fewer overlapping pairs to many
#: shallow ones -- a shallow overlap is not nearly free
COST_OFFSET = 0.01
#: scale the cost of a pair by (area_a x area_b) ** 0.25: overlaps of large
#: copies cost more, so the small ones move out of the way
SIZE_FACTOR = True


def _ring_area(r: np.ndarray) -> float:
    return 0.5 * float(np.dot(r[:, 0], np.roll(r[:, 1], -1)) - np.dot(r[:, 1], np.roll(r[:, 0], -1)))


class PairTable:
    """Packed no-fit polygons of every ordered pair of ``variants``.

    Pair ``p = a * n + b`` (n variants) owns rings ``ring_lo[p] .. ring_hi[p]``;
    ring ``k`` is rows ``pts[start[k] : start[k] + count[k]]`` (x, y of each point, then the
    edge to the next point and its 1 / squared length: :func:`_edge_rows`; float64 grid units,
    outer rings CCW, holes CW: the non-zero rule).  ``bbox[p]`` bounds them;
    a translation outside it cannot overlap.

    ``pair_rings(a, b)`` (optional) gives pair (a, b)'s rings instead of
    :func:`pair_nfp` (the hide separator passes the bottom-left fill's cached
    no-fit polygons of a few variants, :mod:`hide_separation`)."""

    def __init__(self, variants: Sequence[Variant], deadline: float = float("inf"),
                 pair_rings: Optional[Callable[[int, int], List[np.ndarray]]] = None):
        n = len(variants)
        self.n = n
        #: False when ``deadline`` (``time.monotonic()``) passed before every pair was built
        self.complete = True
        rings: List[List[np.ndarray]] = [[] for _ in range(n * n)]
        for a in range(n):
            for b in range(a, n):
                if time.monotonic() > deadline:     # per pair: one row can take seconds
                    self.complete = False
                    break
                if pair_rings is not None:
                    rs = [np.asarray(r, dtype=np.float64) for r in pair_rings(a, b) if len(r) >= 3]
                    rings[a * n + b], rings[b * n + a] = rs, [-r for r in rs]
                    continue
                paths = pair_nfp(variants[a], variants[b])
                if a != b and (variants[a].holes or variants[b].holes):
                    # pair_nfp cuts out only a's holes (b inside a); -NFP(b, a) cuts
                    # out b's (a inside b): the exact NFP is their intersection
                    back = [[[-x, -y] for x, y in r] for r in pair_nfp(variants[b], variants[a])]
                    clip = pyclipper.Pyclipper()
                    clip.AddPaths(paths, pyclipper.PT_SUBJECT, True)
                    clip.AddPaths(back, pyclipper.PT_CLIP, True)
                    paths = clip.Execute(pyclipper.CT_INTERSECTION, pyclipper.PFT_NONZERO,
                                         pyclipper.PFT_NONZERO) if paths and back else []
                rs = [np.asarray(r, dtype=np.float64) for r in paths if len(r) >= 3]
                rings[a * n + b] = rs
                # NFP(b, a) = -NFP(a, b); negating keeps each ring's orientation
                rings[b * n + a] = [-r for r in rs]
            if not self.complete:
                break
        self.pts, self.start, self.count, self.ring_lo, self.ring_hi, self.bbox = pack_rings(rings)
        # cost of an overlapping pair (:func:`copy_penalty`): its depth offset by
        # ``COST_OFFSET`` x the larger diameter, times the pair's size factor
        area = np.array([abs(_ring_area(np.asarray(v.outer, dtype=np.float64))) for v in variants])
        diam = np.array([np.hypot(v.bbox[2] - v.bbox[0], v.bbox[3] - v.bbox[1]) for v in variants])
        size = np.sqrt(np.sqrt(np.outer(area, area)))
        self.cost_offset = (COST_OFFSET * np.maximum.outer(diam, diam)).ravel()
        self.cost_scale = (size / size.mean()).ravel() if SIZE_FACTOR else np.ones(n * n)

    def costs(self):
        """The two per-pair cost arrays :func:`copy_penalty` takes."""
        return self.cost_offset, self.cost_scale

    def arrays(self):
        """The arrays the kernels take, in their order."""
        return self.pts, self.start, self.count, self.ring_lo, self.ring_hi, self.bbox


def pack_rings(rings: Sequence[List[np.ndarray]]):
    """Rings per key (a pair of variants, or a variant) packed for the kernels:
    (edge rows, ring start row, ring length, first ring per key, end ring per
    key, bounding box per key); an empty key gets an empty box (1, 1, -1, -1)."""
    starts, counts, lo, hi, chunks = [], [], [], [], []
    bbox = np.zeros((len(rings), 4))
    off = 0
    for p, rs in enumerate(rings):
        lo.append(len(starts))
        for r in rs:
            starts.append(off)
            counts.append(len(r))
            chunks.append(r)
            off += len(r)
        hi.append(len(starts))
        if rs:
            allp = np.vstack(rs)
            bbox[p] = (allp[:, 0].min(), allp[:, 1].min(), allp[:, 0].max(), allp[:, 1].max())
        else:
            bbox[p] = (1.0, 1.0, -1.0, -1.0)   # empty: never overlaps
    return (_edge_rows(chunks), np.asarray(starts, dtype=np.int64),
            np.asarray(counts, dtype=np.int64), np.asarray(lo, dtype=np.int64),
            np.asarray(hi, dtype=np.int64), bbox)


def _edge_rows(rings: List[np.ndarray]) -> np.ndarray:
    """Rows (x, y, ex, ey, 1 / (ex^2 + ey^2)) of every ring edge, in ring order:
    the edge from each point to the next (the last closes the ring)."""
    if not rings:
        return np.zeros((0, 5))
    out = []
    for r in rings:
        e = np.roll(r, -1, axis=0) - r
        ll = (e * e).sum(axis=1)
        inv = np.divide(1.0, ll, out=np.zeros_like(ll), where=ll > 0.0)
        out.append(np.column_stack([r, e, inv]))
    return np.ascontiguousarray(np.vstack(out))


@njit(cache=True, nogil=True, inline='always')
def pair_depth(tx: float, ty: float, p: int, pts, start, count, ring_lo, ring_hi, bbox) -> float:
    """Penetration depth (grid units) of translation (tx, ty) in pair ``p``'s
    no-fit polygon: 0 outside or on the boundary.  One pass over the edges
    (``pts`` rows: start point, edge vector, 1 / squared length) gives both the
    winding number and the distance to the nearest edge."""
    if tx <= bbox[p, 0] or tx >= bbox[p, 2] or ty <= bbox[p, 1] or ty >= bbox[p, 3]:
        return 0.0
    wind = 0
    best = 1e300
    for k in range(ring_lo[p], ring_hi[p]):
        for q in range(start[k], start[k] + count[k]):
            dx = tx - pts[q, 0]
            dy = ty - pts[q, 1]
            ex = pts[q, 2]
            ey = pts[q, 3]
            ay = pts[q, 1]
            by = ay + ey
            cr = ex * dy - ey * dx
            # winding number and clamped projection without branches (the
            # crossing tests are unpredictable; measured faster)
            wind += np.int64((ay <= ty) & (by > ty) & (cr > 0.0)) \
                - np.int64((ay > ty) & (by <= ty) & (cr < 0.0))
            u = min(max((dx * ex + dy * ey) * pts[q, 4], 0.0), 1.0)
            rx = ex * u - dx
            ry = ey * u - dy
            best = min(best, rx * rx + ry * ry)
    if wind == 0:
        return 0.0
    return np.sqrt(best)


@njit(cache=True, nogil=True, inline='always')
def copy_penalty(i: int, vi: int, x: float, y: float, X, Y, V, W, nv: int, limit: float,
                 order, keys, lo: float, hi: float, coff, cscale, ramp: float,
                 pts, start, count, ring_lo, ring_hi, bbox) -> float:
    """Weighted overlap of copy ``i`` as variant ``vi`` at (x, y) with the other
    copies j (variant V[j] at X[j], Y[j]): sum over the overlapping pairs p of
    W[j] x (depth + coff[p]) x cscale[p] (:meth:`PairTable.costs`); the offset
    grows linearly from 0 over the first ``ramp`` grid units of depth (contact
    within the tolerance stays nearly free and the cost stays continuous).  Broad phase:
    ``order`` sorts the copies by ``keys`` (their left edges); only those with
    a key in [lo, hi] can reach the candidate.  Stops early once the sum
    exceeds ``limit`` (the best candidate so far)."""
    total = 0.0
    k = np.searchsorted(keys, lo)
    end = np.searchsorted(keys, hi, side="right")
    while k < end:
        j = order[k]
        k += 1
        if j == i:
            continue
        p = vi * nv + V[j]
        tx = X[j] - x
        ty = Y[j] - y
        # the box test here, not only in pair_depth: most pairs end at it, and
        # the call alone (not inlined) cost 10x the test (measured, shirts)
        if tx <= bbox[p, 0] or tx >= bbox[p, 2] or ty <= bbox[p, 1] or ty >= bbox[p, 3]:
            continue
        d = pair_depth(tx, ty, p, pts, start, count, ring_lo, ring_hi, bbox)
        if d > 0.0:
            off = coff[p] if d >= ramp else coff[p] * d / ramp
            total += W[j] * (d + off) * cscale[p]
            if total > limit:
                return total
    return total


@njit(cache=True, nogil=True)
def overlap_matrix(X, Y, V, nv: int, pts, start, count, ring_lo, ring_hi, bbox):
    """Unweighted penetration depth of every pair of copies (symmetric, n x n)."""
    n = X.shape[0]
    out = np.zeros((n, n))
    for i in range(n):
        for j in range(i + 1, n):
            p = V[i] * nv + V[j]
            tx = X[j] - X[i]
            ty = Y[j] - Y[i]
            if tx <= bbox[p, 0] or tx >= bbox[p, 2] or ty <= bbox[p, 1] or ty >= bbox[p, 3]:
                continue                # (see copy_penalty)
            d = pair_depth(tx, ty, p, pts, start, count, ring_lo, ring_hi, bbox)
            out[i, j] = d
            out[j, i] = d
    return out
