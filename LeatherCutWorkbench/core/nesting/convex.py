"""Convex pieces of a simple integer ring, for fast no-fit polygons.

The Minkowski sum of two simple polygons is the union of the sums of their
convex pieces, and the sum of two convex polygons is just the convex hull of
their vertex sums.  A ring with r reflex vertices splits into at most about
r + 1 convex pieces, however many vertices its round corners have, so the
no-fit polygon of two arc-rich outlines costs a few dozen small hulls and one
union instead of pyclipper's sweep of every edge pair (the sweep grows with
the product of the vertex counts and was 10x slower on outlines grown by a
round-joined spacing).

Decomposition: constrained Delaunay triangles (shapely / GEOS), then
Hertel-Mehlhorn: remove every inner diagonal whose two pieces still form a
convex polygon.  Written here because no installed library offers a convex
partition.  Exact on integer vertices (the triangles reuse them).
"""

from __future__ import annotations

from typing import Dict, List, Optional, Tuple

import numpy as np

IntPath = List[List[int]]


def _cross(o, a, b) -> int:
    return (a[0] - o[0]) * (b[1] - o[1]) - (a[1] - o[1]) * (b[0] - o[0])


def _is_convex(pts, idx: List[int]) -> bool:
    k = len(idx)
    return all(_cross(pts[idx[i - 1]], pts[idx[i]], pts[idx[(i + 1) % k]]) >= 0 for i in range(k))


def convex_pieces(ring: IntPath) -> Optional[List[IntPath]]:
    """Convex CCW pieces whose union is the simple CCW ``ring``, or None when
    the ring cannot be triangulated (self-touching after rounding): the
    caller then uses the plain sweep."""
    import shapely
    from shapely.geometry import Polygon

    pts = [(int(x), int(y)) for x, y in ring]
    index: Dict[Tuple[int, int], int] = {p: i for i, p in enumerate(pts)}
    if len(index) != len(pts):
        return None
    poly = Polygon(pts)
    if not poly.is_valid:
        return None
    try:
        tris = shapely.constrained_delaunay_triangles(poly)
    except Exception:          # GEOS refuses the ring: fall back to the sweep
        return None
    coords = shapely.get_coordinates(shapely.get_exterior_ring(shapely.get_parts(tris)))
    if len(coords) % 4:
        return None
    pieces: List[List[int]] = []
    for x0, y0, x1, y1, x2, y2 in np.rint(coords.reshape(-1, 4, 2)[:, :3, :]).astype(np.int64) \
            .reshape(-1, 6).tolist():
        c = [index.get((x0, y0)), index.get((x1, y1)), index.get((x2, y2))]
        if None in c:
            return None
        if _cross(pts[c[0]], pts[c[1]], pts[c[2]]) < 0:
            c.reverse()
        pieces.append(c)
    if abs(sum(abs(_cross(pts[c[0]], pts[c[1]], pts[c[2]])) for c in pieces) -
           2 * abs(poly.area)) > 1e-6 * 2 * abs(poly.area) + 2:
        return None            # triangles do not tile the ring
    # Hertel-Mehlhorn: one pass over the inner diagonals, merging where convex
    live: Dict[int, List[int]] = dict(enumerate(pieces))
    owner: Dict[Tuple[int, int], int] = {}
    for pi, c in live.items():
        for k in range(len(c)):
            owner[(c[k], c[(k + 1) % len(c)])] = pi
    diagonals = [e for e in owner if e[0] < e[1] and (e[1], e[0]) in owner]
    for a, b in diagonals:
        pi, pj = owner.get((a, b)), owner.get((b, a))
        if pi is None or pj is None or pi == pj:
            continue
        ci, cj = live[pi], live[pj]
        ka, kb = ci.index(a), cj.index(b)
        walk_i = ci[ka + 1:] + ci[:ka + 1]           # b ... a
        walk_j = cj[kb + 1:] + cj[:kb + 1]           # a ... b
        cand = walk_i + walk_j[1:-1]
        if not _is_convex(pts, cand):
            continue
        del live[pj]
        del owner[(a, b)], owner[(b, a)]
        live[pi] = cand
        for k in range(len(cand)):
            owner[(cand[k], cand[(k + 1) % len(cand)])] = pi
    pieces = list(live.values())
    return [[list(pts[i]) for i in c] for c in pieces]


Form = Tuple[np.ndarray, np.ndarray, np.ndarray]


def edge_form(ring: IntPath) -> Form:
    """A convex CCW ring as (lowest vertex, edge vectors, edge angles in
    [0, 2 pi)) starting at its lowest (then leftmost) vertex: the input of
    :func:`sum_forms`."""
    a = np.asarray(ring, dtype=np.int64)
    k = int(np.lexsort((a[:, 0], a[:, 1]))[0])
    a = np.roll(a, -k, axis=0)
    e = np.roll(a, -1, axis=0) - a
    ang = np.mod(np.arctan2(e[:, 1], e[:, 0]), 2.0 * np.pi)
    return a[0], e, ang


def sum_forms(fa: Form, fb: Form) -> IntPath:
    """Minkowski sum of two convex rings given as edge forms: the edges merged
    by angle from the sum of the lowest vertices (exact integers, CCW)."""
    e = np.concatenate((fa[1], fb[1]))
    order = np.argsort(np.concatenate((fa[2], fb[2])), kind="stable")
    pts = np.cumsum(e[order[:-1]], axis=0) + (fa[0] + fb[0])
    return np.vstack(((fa[0] + fb[0])[None, :], pts)).tolist()


def convex_sum(a: IntPath, b: IntPath) -> IntPath:
    """Minkowski sum of two convex CCW rings (exact integers, CCW)."""
    return sum_forms(edge_form(a), edge_form(b))
