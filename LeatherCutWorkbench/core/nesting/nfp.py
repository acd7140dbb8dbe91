"""No-fit and inner-fit polygons on the integer grid (pyclipper).

For a fixed piece A (at the origin) and a moving piece B, the no-fit polygon
``NFP(A, B)`` is the set of translations t of B's reference point for which
B + t overlaps A: the Minkowski sum A (+) (-B).  pyclipper's ``MinkowskiSum``
of a closed path sweeps -B along A's boundary; the union with A shifted by one
vertex of -B (B's vertex inside A) and with -B shifted by a vertex of A (A
inside B) fills the interior.  Only the outer boundary of that union is kept
(rounding leaves sliver holes and degenerate islands; a genuine locked pocket
is rare and dropping it is safe).  Holes
of A (already shrunk by the spacing) give "part-in-part" islands: the translations that put B wholly inside the hole, i.e. the hole
shifted by -b0 minus the sweep of -B along the hole boundary; they are cut
out of the solid NFP, so one region per pair covers both cases.

When both rings are convex the sum is simply the convex hull of all vertex sums
(scipy), several times faster and exact in integers.

The inner-fit region of a container region R (outer rings, defect / forbidden
holes) is built the same way: R's outer ring shifted by -b0 minus the sweep
along its boundary, minus the full NFP of every hole.

Orientation convention: regions CCW, holes CW; every union / difference uses
the non-zero fill rule, so a list of regions-with-holes can be added as is.
"""

from __future__ import annotations

from typing import Dict, List, Sequence, Tuple

import numpy as np
import pyclipper

from .shapes import IntPath, Variant

_NZ = pyclipper.PFT_NONZERO


def _clip(subject: Sequence[IntPath], clip: Sequence[IntPath], op: int) -> List[IntPath]:
    c = pyclipper.Pyclipper()
    if subject:
        c.AddPaths(list(subject), pyclipper.PT_SUBJECT, True)
    if clip:
        c.AddPaths(list(clip), pyclipper.PT_CLIP, True)
    if not subject:
        return []
    return c.Execute(op, _NZ, _NZ)


def union(paths: Sequence[IntPath]) -> List[IntPath]:
    return _clip(paths, [], pyclipper.CT_UNION)


def difference(subject: Sequence[IntPath], clip: Sequence[IntPath]) -> List[IntPath]:
    if not clip:
        return [list(p) for p in subject]
    return _clip(subject, clip, pyclipper.CT_DIFFERENCE)


def _neg(path: IntPath) -> IntPath:
    return [[-x, -y] for x, y in path]


def _shift(path: IntPath, dx: int, dy: int) -> IntPath:
    return [[x + dx, y + dy] for x, y in path]


def is_convex(ring: IntPath) -> bool:
    """Does the CCW ring turn left (or go straight) at every vertex?"""
    a = np.asarray(ring, dtype=np.float64)
    d = np.roll(a, -1, axis=0) - a
    cross = d[:, 0] * np.roll(d[:, 1], -1) - d[:, 1] * np.roll(d[:, 0], -1)
    return bool((cross >= 0).all())


def _convex_sum(a_outer: IntPath, nb: IntPath) -> IntPath:
    """Minkowski sum of two convex rings: the convex hull of all vertex sums
    (exact integers, counter-clockwise)."""
    from scipy.spatial import ConvexHull
    a = np.asarray(a_outer, dtype=np.int64)
    b = np.asarray(nb, dtype=np.int64)
    pts = (a[:, None, :] + b[None, :, :]).reshape(-1, 2)
    hull = ConvexHull(pts.astype(np.float64))
    return pts[hull.vertices].tolist()


def solid_nfp(a_outer: IntPath, b_outer: IntPath) -> List[IntPath]:
    """A (+) (-B) for two simple CCW rings: translations of B that overlap A."""
    nb = _neg(b_outer)
    if is_convex(a_outer) and is_convex(b_outer):
        return [_convex_sum(a_outer, nb)]       # fast path: hull of vertex sums
    sweep = pyclipper.MinkowskiSum(nb, a_outer, True)
    base = _shift(a_outer, nb[0][0], nb[0][1])           # B's vertex inside A
    cover = _shift(nb, a_outer[0][0], a_outer[0][1])      # A's vertex inside B
    # The sum of two connected shapes is connected: keep the outer boundary only.
    # Rounding leaves sliver holes (and degenerate islands inside them) between
    # nearly parallel edges; a genuine locked pocket is rare -- dropping is safe.
    outers = [p for p in union(list(sweep) + [base, cover]) if pyclipper.Orientation(p)]
    return [max(outers, key=pyclipper.Area)] if outers else []


def inner_fit(region_outer: IntPath, b_outer: IntPath) -> List[IntPath]:
    """Translations of B that keep it inside the simple CCW ring ``region_outer``."""
    nb = _neg(b_outer)
    sweep = pyclipper.MinkowskiSum(nb, region_outer, True)
    # grow the swept band by two grid units: rounding slivers left inside it must
    # not become (infeasible) free positions
    off = pyclipper.PyclipperOffset()
    off.AddPaths(sweep, pyclipper.JT_MITER, pyclipper.ET_CLOSEDPOLYGON)
    band = off.Execute(2.0)
    inside = _shift(region_outer, -b_outer[0][0], -b_outer[0][1])
    return difference([inside], band)


def pair_nfp(a: Variant, b: Variant) -> List[IntPath]:
    """NFP of variant ``b`` around variant ``a`` with part-in-part islands."""
    solid = solid_nfp(a.outer, b.outer)
    if not a.holes:
        return solid
    islands: List[IntPath] = []
    bw, bh = b.bbox[2] - b.bbox[0], b.bbox[3] - b.bbox[1]
    for h in a.holes:
        xs = [p[0] for p in h]
        ys = [p[1] for p in h]
        if max(xs) - min(xs) < bw or max(ys) - min(ys) < bh:
            continue                          # B cannot fit: skip the sweep
        islands.extend(inner_fit(h, b.outer))
    return difference(solid, islands) if islands else solid


def region_ifp(outers: Sequence[IntPath], obstacles: Sequence[IntPath], b_outer: IntPath) -> List[IntPath]:
    """Inner-fit region of the ring ``b_outer`` in a container made of simple CCW
    ``outers`` with ``obstacles`` (CCW rings: defects, forbidden zones) it must
    not overlap."""
    fits: List[IntPath] = []
    for o in outers:
        fits.extend(inner_fit(o, b_outer))
    if not fits:
        return []
    blocked: List[IntPath] = []
    for ob in obstacles:
        blocked.extend(solid_nfp(ob, b_outer))
    return difference(fits, blocked) if blocked else fits


class NfpCache:
    """Pairwise NFPs of variants, computed on first use, as numpy arrays
    (translation by a placement is then one vectorised add)."""

    def __init__(self, variants: Sequence[Variant]):
        self.variants = variants
        self._cache: Dict[Tuple[int, int], Tuple[List[np.ndarray], Tuple[int, int, int, int]]] = {}

    def get(self, a: int, b: int) -> Tuple[List[np.ndarray], Tuple[int, int, int, int]]:
        key = (a, b)
        hit = self._cache.get(key)
        if hit is None:
            paths = pair_nfp(self.variants[a], self.variants[b])
            arrs = [np.asarray(p, dtype=np.int64) for p in paths if len(p) >= 3]
            if arrs:
                allp = np.vstack(arrs)
                bb = (int(allp[:, 0].min()), int(allp[:, 1].min()),
                      int(allp[:, 0].max()), int(allp[:, 1].max()))
            else:
                bb = (0, 0, -1, -1)
            hit = (arrs, bb)
            self._cache[key] = hit
        return hit
