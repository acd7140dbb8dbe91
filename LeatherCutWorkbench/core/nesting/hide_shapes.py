"""Part outlines with fewer vertices for hide nesting.

Leather parts (car seats, shoe uppers) come as finely flattened curves: a
Baldacci Test2 part has about 100 vertices.  No-fit polygons of two such
parts (unions of the sums of their convex pieces) then take ~50 ms and the
inner-fit region of one in a hide outline (a sweep of vertices x vertices)
~10 ms, so a first fill of 34 parts on 12 hides with 12 orientations would
not end within a 10 s budget.

:func:`simplify_for_hides` replaces each variant's outline by a ring that
*contains* it: grown by ``frac`` of the variant's size, then simplified
(Douglas-Peucker, shapely) within 90 % of that growth, so every layout of
the simplified rings is a valid layout of the true parts (the independent
checker re-checks the true shapes).  The price is a gap of at most
2 x ``frac`` x size between parts and ``frac`` x size at the hide's edges.
Holes (parts in holes of parts) are kept exact.  ``frac`` = 0.2 %: with
0.08 % an exact first fill of Test2 took 2-3 times longer (more convex
pieces per NFP) for the same hides.

:class:`HullPockets` computes inner-fit regions of convex part hulls in a
hide outline from the outline's convex hull minus its pockets (convex sums)
instead of a sweep along every outline vertex.  The part's own convex
pieces against the pockets instead of its hull give the exact region (about
twice the time per region, 5 against 2.5 ms on Test2; a first fill 1.5x):
``blf.Placer.concave_fit``, used by the copy-to-hide worker, whose tight hide
sets need the copies a concave stretch of the outline would keep out.
"""

from __future__ import annotations

from dataclasses import replace
from typing import List, Optional, Sequence, Tuple

import numpy as np
import pyclipper
import shapely
from shapely.geometry import Polygon

from .convex import convex_pieces
from .convex_sums import FormSet, sum_all
from .shapes import IntPath, Variant, convex_hull

#: growth, as a fraction of a variant's larger bounding-box side (module doc)
HIDE_SIMPLIFY = 0.002

#: only outlines with more vertices than this are simplified
_MIN_VERTICES = 16


def _supersets(rings: Sequence[IntPath], ds: Sequence[float]) -> List[IntPath]:
    """Per ring a CCW grid ring containing it: grown by its ``d`` grid units
    (mitred, bevelled beyond 2 d), simplified within 0.9 ``d``; the ring
    itself when that does not save vertices or the rounded result does not
    cover it (a simplification that cut a corner).  shapely's array
    functions, one call per step for all rings: a Polygon per ring cost
    0.35 s of preparing Baldacci Test10's 204 orientations."""
    if not rings:
        return []
    coords = np.concatenate([np.asarray(r, dtype=float) for r in rings])
    index = np.repeat(np.arange(len(rings)), [len(r) for r in rings])
    polys = shapely.polygons(shapely.linearrings(coords, indices=index))
    d = np.asarray(ds, dtype=float)
    grown = shapely.simplify(shapely.buffer(polys, d, quad_segs=4, join_style="mitre",
                                            mitre_limit=2.0), 0.9 * d)
    candidates: List[Optional[IntPath]] = []
    for ring, g in zip(rings, grown):
        ring_out = None
        if g is not None and not g.is_empty and g.geom_type == "Polygon":
            ring_out = np.rint(shapely.get_coordinates(g.exterior)[:-1]).astype(np.int64).tolist()
        candidates.append(ring_out if ring_out is not None and 3 <= len(ring_out) < len(ring)
                          else None)
    sel = [i for i, c in enumerate(candidates) if c is not None]
    if sel:
        cand = np.array([shapely.polygons(candidates[i]) for i in sel], dtype=object)
        for i, ok in zip(sel, shapely.covers(cand, polys[sel])):
            if not ok:
                candidates[i] = None
    return [ring if c is None else (c if pyclipper.Orientation(c) else c[::-1])
            for ring, c in zip(rings, candidates)]


def _superset(ring: IntPath, d: float) -> IntPath:
    """:func:`_supersets` of one ring."""
    return _supersets([ring], [d])[0]


def simplify_for_hides(variants: Sequence[Variant], frac: float = HIDE_SIMPLIFY) -> List[Variant]:
    """Variants whose ``outer`` / ``core`` are replaced by simplified rings that
    contain them (see module doc); bbox and hulls follow."""
    # (up to _MIN_VERTICES vertices or under 8 grid units of growth: too small
    # a part to gain anything)
    grow = {i: frac * max(v.bbox[2] - v.bbox[0], v.bbox[3] - v.bbox[1])
            for i, v in enumerate(variants)}
    todo = [i for i, v in enumerate(variants) if len(v.outer) > _MIN_VERTICES and grow[i] >= 8]
    ds = [grow[i] for i in todo]
    rings = _supersets([variants[i].outer for i in todo] + [variants[i].core for i in todo],
                       ds + ds)
    out: List[Variant] = list(variants)
    for k, i in enumerate(todo):
        outer, core = rings[k], rings[len(todo) + k]
        xs = [p[0] for p in outer]
        ys = [p[1] for p in outer]
        out[i] = replace(variants[i], outer=outer, core=core,
                         bbox=(min(xs), min(ys), max(xs), max(ys)),
                         hull=convex_hull(outer), core_hull=convex_hull(core))
    return out


def superset_rings(rings: Sequence[Tuple[int, IntPath]], v: Variant,
                   frac: float = HIDE_SIMPLIFY) -> List[Tuple[int, IntPath]]:
    """(grade, ring) of a variant's graded part regions, each ring replaced by
    one containing it (grown by ``frac`` of the variant's size, simplified:
    :func:`_superset`), so an inner-fit region of the new ring is one of the
    true region; rings of up to ``_MIN_VERTICES`` vertices stay."""
    d = frac * max(v.bbox[2] - v.bbox[0], v.bbox[3] - v.bbox[1])
    return [(g, _superset(r, d) if len(r) > _MIN_VERTICES and d >= 8 else r) for g, r in rings]


class HullPockets:
    """A hide region's outer rings as (convex hull, convex pieces of the
    pockets between hull and ring) for fast inner-fit regions of convex rings.

    ``x + B`` lies in a ring R exactly when it lies in R's convex hull H and
    overlaps no pocket H \\ R, so for a convex B the inner-fit region is the
    sweep of B in H (few vertices) minus the convex sums pocket piece (+) -B
    -- a few milliseconds instead of a sweep along R's every vertex.  An outer
    ring whose pockets cannot be decomposed keeps the plain sweep (``None``)."""

    def __init__(self, outers: Sequence[IntPath]):
        from .nfp import edge_form
        self.outers = [list(o) for o in outers]
        self.parts: List[Tuple[IntPath, object]] = []
        #: per outer: the pockets as (CCW ring, FormSet of its convex pieces)
        self.pockets: List[List[Tuple[IntPath, object]]] = []
        for o in outers:
            hull = convex_hull(o)
            forms: Optional[list] = []
            pockets: List[Tuple[IntPath, object]] = []
            gap = Polygon(hull).difference(Polygon(o))
            for g in getattr(gap, "geoms", [gap]):
                if g.is_empty or g.geom_type != "Polygon" or g.area <= 0:
                    continue
                ring = [[int(round(x)), int(round(y))] for x, y in list(g.exterior.coords)[:-1]]
                if not pyclipper.Orientation(ring):
                    ring = ring[::-1]
                pieces = convex_pieces(ring) if len(ring) >= 3 else []
                if pieces is None:
                    forms = None
                    break
                forms.extend(edge_form(p) for p in pieces)
                if pieces:
                    pockets.append((ring, FormSet([edge_form(p) for p in pieces])))
            self.parts.append((hull if forms is not None else o,
                               FormSet(forms) if forms else forms))
            self.pockets.append(pockets if forms is not None else [])

    def ifp(self, b_hull: IntPath, b: Optional[IntPath] = None) -> List[IntPath]:
        """Translations of the convex CCW ring ``b_hull`` inside the outers.

        With ``b`` (a CCW ring whose convex hull is ``b_hull``): exactly the
        translations of ``b`` inside the outers -- inside a convex hull exactly
        when its hull is, overlapping no pocket: the pockets' sums with -``b``'s
        convex pieces.  (Baldacci Test10's graded part regions: 1 s per region
        for the plain sweep of the 300-vertex hide outline, ~40x faster so.)
        An outer without pockets' pieces, or a ``b`` that cannot be decomposed,
        gets the plain sweep of ``b``."""
        from .nfp import _neg, difference, edge_form, inner_fit, piece_forms, solid_nfp
        bw = max(p[0] for p in b_hull) - min(p[0] for p in b_hull)
        bh = max(p[1] for p in b_hull) - min(p[1] for p in b_hull)
        nb = FormSet([edge_form(_neg(b_hull))]) if b is None else piece_forms(b, negate=True)
        fits: List[IntPath] = []
        for outer, (ring, forms), pockets in zip(self.outers, self.parts, self.pockets):
            if max(p[0] for p in ring) - min(p[0] for p in ring) < bw or \
                    max(p[1] for p in ring) - min(p[1] for p in ring) < bh:
                continue
            if b is not None and forms and nb is None:
                fits.extend(inner_fit(outer, b))
                continue
            fit = inner_fit(ring, b_hull if b is None or forms is not None else b)
            if forms and fit:
                if b is None:
                    fit = difference(fit, sum_all(forms, nb))
                else:
                    # per pocket the solid sum (its holes filled: ``b`` around a
                    # pocket would leave the hull), then one difference
                    blocked = [r for ring_p, fp in pockets for r in solid_nfp(ring_p, b, fp, nb)]
                    fit = difference(fit, blocked)
            fits.extend(fit)
        return fits
