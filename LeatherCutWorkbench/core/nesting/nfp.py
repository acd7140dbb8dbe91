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

Coarse no-fit polygons (:class:`NfpCache` under time pressure, see
:class:`Clock`) are the sums of the two variants' convex hulls: a superset of
the exact NFP, so a layout built with them is still valid, only less dense.
Computing one costs a fraction of a millisecond instead of the 5-30 ms of an
exact sum of two arc-rich outlines.

The inner-fit region of a container region R (outer rings, defect / forbidden
holes) is built the same way: R's outer ring shifted by -b0 minus the sweep
along its boundary, minus the full NFP of every hole.

Orientation convention: regions CCW, holes CW; every union / difference uses
the non-zero fill rule, so a list of regions-with-holes can be added as is.
"""

from __future__ import annotations

import math
import time
from dataclasses import dataclass
from typing import Callable, Dict, List, Optional, Sequence, Tuple

import numpy as np
import pyclipper

from .convex import Form, convex_pieces, convex_sum, edge_form, sum_forms
from .convex_sums import FormSet, sum_all
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
    """Does the CCW ring turn left (or go straight) at every vertex?  (Exact
    integers; a plain loop beats numpy on the few vertices rings have here.)"""
    n = len(ring)
    for i in range(n):
        (ax, ay), (bx, by), (cx, cy) = ring[i - 2], ring[i - 1], ring[i]
        if (bx - ax) * (cy - by) - (by - ay) * (cx - bx) < 0:
            return False
    return True


def obstacle_forms(ring: IntPath) -> Forms:
    """Edge forms of an obstacle ring for :func:`region_ifp` (one form when convex)."""
    return FormSet([edge_form(ring)]) if is_convex(ring) else piece_forms(ring)


Forms = Optional[List[Form]]


def piece_forms(ring: IntPath, negate: bool = False) -> Forms:
    """Edge forms of the convex pieces of ``ring`` (of ``-ring`` with
    ``negate``), or None when it cannot be decomposed."""
    if is_convex(ring):
        return FormSet([edge_form(_neg(ring) if negate else ring)])
    pieces = convex_pieces(ring)
    if pieces is None:
        return None
    return FormSet([edge_form(_neg(p) if negate else p) for p in pieces])


def _tree_union(paths: List[IntPath], group: int = 8) -> List[IntPath]:
    """Union of many overlapping convex rings, eight at a time (pyclipper is
    about twice as fast on small groups as on hundreds of rings at once)."""
    while len(paths) > group:
        merged: List[IntPath] = []
        for k in range(0, len(paths), group):
            merged.extend(union(paths[k:k + group]))
        if len(merged) >= len(paths):
            break
        paths = merged
    return union(paths)


def solid_nfp(a_outer: IntPath, b_outer: IntPath, a_forms: Forms = None,
              nb_forms: Forms = None) -> List[IntPath]:
    """A (+) (-B) for two simple CCW rings: translations of B that overlap A.

    ``a_forms`` / ``nb_forms``: edge forms of the convex pieces of A and of
    -B (:func:`piece_forms`, computed here when not given); the sum is the
    union of the pieces' convex sums.  When a ring cannot be decomposed
    pyclipper's edge sweep is used."""
    nb = _neg(b_outer)
    if a_forms is not None and nb_forms is not None and len(a_forms) == 1 == len(nb_forms):
        return [sum_forms(a_forms[0], nb_forms[0])]      # both convex: one convex sum
    if is_convex(a_outer) and is_convex(b_outer):
        return [convex_sum(a_outer, nb)]       # fast path: one convex sum
    pa = a_forms if a_forms is not None else piece_forms(a_outer)
    pb = nb_forms if nb_forms is not None else piece_forms(b_outer, negate=True)
    if pa and pb:
        outers = [p for p in _tree_union(sum_all(pa, pb))
                  if pyclipper.Orientation(p)]
        return [max(outers, key=pyclipper.Area)] if outers else []
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


def pair_nfp(a: Variant, b: Variant, a_forms: Forms = None,
             nb_forms: Forms = None) -> List[IntPath]:
    """NFP of variant ``b`` around variant ``a`` with part-in-part islands."""
    solid = solid_nfp(a.outer, b.outer, a_forms, nb_forms)
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


def region_ifp(outers: Sequence[IntPath], obstacles: Sequence[IntPath], b_outer: IntPath,
               ob_forms: "Sequence[Forms] | None" = None,
               fits: "List[IntPath] | None" = None) -> List[IntPath]:
    """Inner-fit region of the ring ``b_outer`` in a container made of simple CCW
    ``outers`` with ``obstacles`` (CCW rings: defects, forbidden zones) it must
    not overlap; ``ob_forms``: the obstacles' :func:`obstacle_forms` (the
    same for every part, so the caller keeps them).  ``fits``: the inner-fit
    region in the ``outers`` computed by the caller (then the outers are not
    swept; the obstacles always see ``b_outer`` itself)."""
    if fits is None:
        fits = []
        bw = max(p[0] for p in b_outer) - min(p[0] for p in b_outer)
        bh = max(p[1] for p in b_outer) - min(p[1] for p in b_outer)
        for o in outers:
            if max(p[0] for p in o) - min(p[0] for p in o) < bw or \
                    max(p[1] for p in o) - min(p[1] for p in o) < bh:
                continue                      # too narrow for B: skip the sweep
            fits.extend(inner_fit(o, b_outer))
    else:
        fits = list(fits)
    if not fits:
        return []
    blocked: List[IntPath] = []
    nb_forms = piece_forms(b_outer, negate=True)      # once for every obstacle
    forms = ob_forms if ob_forms is not None else [obstacle_forms(ob) for ob in obstacles]
    for ob, fa in zip(obstacles, forms):
        blocked.extend(solid_nfp(ob, b_outer, fa, nb_forms))
    return difference(fits, blocked) if blocked else fits


@dataclass
class Clock:
    """Deadlines (``time.monotonic()`` seconds) the placer honours.

    * ``stop_at`` -- an evaluation still running then is abandoned (the first
      fill of a search is never abandoned, see ``exact_until``);
    * ``exact_until`` -- exact NFPs / inner-fit regions not yet cached are
      computed only before this; later the convex-hull ones are used (valid,
      coarser, fast), so even a fill of hundreds of arc-rich parts ends soon;
    * ``hard_stop`` -- on a hopelessly loaded machine the first fill goes on
      with bounding-box no-fit polygons from here;
    * ``give_up_at`` -- and stops here: the copies it did not reach are
      reported unplaced."""

    stop_at: float = math.inf
    exact_until: float = math.inf
    stop: "Callable[[], bool] | None" = None      # the user pressed Stop
    #: from here on even the first fill uses bounding boxes only (fastest, coarsest)
    hard_stop: float = math.inf
    #: the first fill ends here: the copies not placed yet stay unplaced
    give_up_at: float = math.inf

    def boxes(self) -> bool:
        return self.hard_stop != math.inf and time.monotonic() > self.hard_stop

    def exact(self) -> bool:
        """May an exact NFP still be computed?  (Not once past a deadline.)"""
        if self.expired():
            return False
        return self.exact_until == math.inf or time.monotonic() < self.exact_until

    def expired(self) -> bool:
        if self.stop is not None and self.stop():
            return True
        return self.stop_at != math.inf and time.monotonic() > self.stop_at


class NfpCache:
    """Pairwise NFPs of variants, computed on first use, as numpy arrays
    (translation by a placement is then one vectorised add).  While the
    clock allows, exact; afterwards a pair not yet cached gets its coarse
    (convex-hull) NFP."""

    def __init__(self, variants: Sequence[Variant], clock: "Clock | None" = None):
        self.variants = variants
        self.clock = clock or Clock()
        self._cache: Dict[Tuple[int, int], Tuple[List[np.ndarray], Tuple[int, int, int, int]]] = {}
        self._coarse: Dict[Tuple[int, int], Tuple[List[np.ndarray], Tuple[int, int, int, int]]] = {}
        self.exact_s = 0.0                 # seconds spent on exact NFPs
        self._hull_forms: Dict[int, Tuple[Form, Form]] = {}
        self._piece_forms: Dict[int, Tuple[Forms, Forms]] = {}

    def mean_exact_s(self) -> float:
        """Mean seconds per exact NFP so far (0 before the first)."""
        return self.exact_s / len(self._cache) if self._cache else 0.0

    def hull_forms(self, v: int) -> Tuple[Form, Form]:
        """Edge forms of variant ``v``'s convex hull and of its negation (cached)."""
        hit = self._hull_forms.get(v)
        if hit is None:
            hull = self.variants[v].hull
            hit = self._hull_forms[v] = (edge_form(hull), edge_form(_neg(hull)))
        return hit

    def piece_forms(self, v: int) -> Tuple[Forms, Forms]:
        """Edge forms of variant ``v``'s convex pieces and of their negations
        (cached; None: the outline could not be decomposed)."""
        if v not in self._piece_forms:
            pieces = convex_pieces(self.variants[v].outer)
            self._piece_forms[v] = (None, None) if pieces is None else (
                FormSet([edge_form(p) for p in pieces]),
                FormSet([edge_form(_neg(p)) for p in pieces]))
        return self._piece_forms[v]

    def get(self, a: int, b: int) -> Tuple[List[np.ndarray], Tuple[int, int, int, int]]:
        key = (a, b)
        hit = self._cache.get(key)
        if hit is not None:
            return hit
        if self.clock.exact():
            t0 = time.monotonic()
            hit = _arrays(pair_nfp(self.variants[a], self.variants[b],
                                   self.piece_forms(a)[0], self.piece_forms(b)[1]))
            self.exact_s += time.monotonic() - t0
            self._cache[key] = hit
            return hit
        hit = self._coarse.get(key)
        if hit is None and self.clock.boxes():
            (ax0, ay0, ax1, ay1), (bx0, by0, bx1, by1) = self.variants[a].bbox, self.variants[b].bbox
            return _arrays([[[ax0 - bx1, ay0 - by1], [ax1 - bx0, ay0 - by1],
                             [ax1 - bx0, ay1 - by0], [ax0 - bx1, ay1 - by0]]])
        if hit is None:
            hit = _arrays([sum_forms(self.hull_forms(a)[0], self.hull_forms(b)[1])])
            self._coarse[key] = hit
        return hit


def _arrays(paths: List[IntPath]) -> Tuple[List[np.ndarray], Tuple[int, int, int, int]]:
    """Paths as int64 arrays plus their bounding box."""
    arrs = [np.asarray(p, dtype=np.int64) for p in paths if len(p) >= 3]
    if not arrs:
        return arrs, (0, 0, -1, -1)
    allp = np.vstack(arrs)
    return arrs, (int(allp[:, 0].min()), int(allp[:, 1].min()),
                  int(allp[:, 0].max()), int(allp[:, 1].max()))
