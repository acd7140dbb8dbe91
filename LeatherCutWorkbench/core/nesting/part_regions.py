"""Part regions with their own grade (a shoe upper's visible zone needs grade A,
the rest of the part may lie on grade B).

A part of grade p with regions (g_k, R_k) (``Part.grade_regions``, closed
contours inside the part's outer contour, in part coordinates) is split into
*pieces*: each region clipped to the part (where regions overlap, the
smallest one decides, as for hide zones) with its grade g_k, and the rest of
the part with grade p.  A placement on a hide is valid when every piece lies
where the hide's grade is >= the piece's grade (see
:func:`containers.usable_region`).  A region of grade 0 may lie anywhere on
the hide, holes and defects included (Baldacci's Test8 item i_3: a frame
whose window, quality 0, is cut away); every other piece avoids defects.

The engine nests such a part with its most permissive grade (the lowest of p
and the g_k, at least 1 so the whole part still avoids defects: a window
over a hole is never *sought*, only allowed by the checker) and
:class:`RegionCheck` rejects candidate positions where a stricter piece
would cover material below its grade.  The independent checker
(:mod:`checker`) and the report (:func:`region_grades`) use
:func:`pieces` and :func:`containers.usable_region` as well.
"""

from __future__ import annotations

import math
from typing import Dict, List, Optional, Sequence, Tuple

from shapely import affinity
from shapely.geometry import Polygon
from shapely.geometry.base import BaseGeometry
from shapely.prepared import prep

from ..model import Container, Part
from .containers import usable_region


def pieces(part: Part, chord_tol: float = 0.05) -> List[Tuple[int, BaseGeometry, str]]:
    """(grade, shape in part coordinates, label) per piece of ``part``: its
    regions (label ``region k``), then the rest (label ``rest``).  A part
    without regions is one piece of its own grade."""
    whole = Polygon(part.outer.points(chord_tol), [h.points(chord_tol) for h in part.holes])
    if not part.grade_regions:
        return [(part.grade, whole, "rest")]
    regs = [(g, Polygon(c.points(chord_tol)), k) for k, (g, c) in enumerate(part.grade_regions)]
    out: List[Tuple[int, BaseGeometry, str]] = []
    taken: BaseGeometry = Polygon()
    for g, poly, k in sorted(regs, key=lambda r: r[1].area):      # smallest decides
        piece = poly.intersection(whole).difference(taken)
        taken = taken.union(poly)
        if not piece.is_empty and piece.area > 0:
            out.append((g, piece, f"region {k}"))
    rest = whole.difference(taken)
    if not rest.is_empty and rest.area > 0:
        out.append((part.grade, rest, "rest"))
    return out


def nesting_grade(part: Part) -> int:
    """The grade the engine nests ``part`` with: the lowest grade of its pieces,
    at least 1 when the part has regions (see module doc)."""
    if not part.grade_regions:
        return part.grade
    return max(1, min([part.grade] + [g for g, _c in part.grade_regions]))


def material_grade(shape: BaseGeometry, c: Container, tol: float,
                   cache: Optional[Dict[Tuple[str, int], tuple]] = None) -> int:
    """The lowest hide grade under ``shape`` (placed, mm): the best level g of
    ``c`` whose usable region holds it within ``tol`` x its perimeter (0 when
    it covers a defect or leaves the outline).  ``cache`` keeps each level's
    region and its prepared form per hide: most shapes lie wholly inside, which
    the prepared ``covers`` answers without the difference."""
    levels = sorted({c.base_grade} | {zg for zg, _ in c.zones}, reverse=True)
    cache = {} if cache is None else cache
    for lv in levels:
        key = (c.id, lv)
        if key not in cache:
            region = usable_region(c, lv)
            cache[key] = (region, prep(region))
        region, inside = cache[key]
        if inside.covers(shape) or shape.difference(region).area <= tol * shape.length:
            return lv
    return 0


def region_grades(part: Part, placed_pieces: Sequence[Tuple[int, BaseGeometry, str]],
                  c: Container, tol: float,
                  cache: Optional[Dict[Tuple[str, int], BaseGeometry]] = None) -> List[Dict]:
    """Report rows for a placed part with regions: per piece its label, the grade
    it needs and the grade of the material it lies on."""
    return [{"piece": label, "grade": g, "material_grade": material_grade(shape, c, tol, cache)}
            for g, shape, label in placed_pieces]


class RegionCheck:
    """Candidate-position test for parts with regions (engine side).

    ``types[t]`` = the pieces (grade, shape in part coordinates) of type t that
    are stricter than the grade it is nested with (None: no test);
    ``hides[b]`` = the hide of bin spec b.  Geometry is prepared lazily in the
    worker process (prepared geometries do not pickle)."""

    def __init__(self, types: Sequence[Optional[List[Tuple[int, BaseGeometry]]]],
                 hides: Sequence[Container], scale: float, tol: float,
                 rings: Optional[Sequence[List[Tuple[int, List[Tuple[float, float]]]]]] = None):
        self.types = list(types)
        self.hides = list(hides)
        self.scale = scale
        self.tol = tol
        #: per type: (grade, outer ring in part coordinates) of its stricter regions
        self.rings = list(rings) if rings is not None else [[] for _ in self.types]
        self._bad: Dict[Tuple[int, int], object] = {}
        self._shapes: Dict[Tuple[int, float, bool], List[Tuple[int, BaseGeometry]]] = {}

    def __getstate__(self):
        return {"types": self.types, "hides": self.hides, "scale": self.scale, "tol": self.tol,
                "rings": self.rings}

    def __setstate__(self, state):
        self.__init__(state["types"], state["hides"], state["scale"], state["tol"],
                      state["rings"])

    def grid_rings(self, t: int, angle: float, mirrored: bool) -> List[Tuple[int, list]]:
        """(grade, CCW grid ring) of type ``t``'s stricter regions in the frame of
        its variant (mirror about the Y axis, rotate about the origin, scale):
        the engine intersects the variant's inner-fit region with theirs."""
        import pyclipper
        out = []
        a = math.radians(angle)
        ca, sa = math.cos(a), math.sin(a)
        for g, ring in self.rings[t]:
            pts = []
            for x, y in ring:
                x = -x if mirrored else x
                pts.append([int(round((x * ca - y * sa) * self.scale)),
                            int(round((x * sa + y * ca) * self.scale))])
            if not pyclipper.Orientation(pts):
                pts.reverse()
            out.append((g, pts))
        return out

    def applies(self, t: int) -> bool:
        return t < len(self.types) and self.types[t] is not None

    def strictest(self, t: int) -> int:
        """The strictest grade type ``t``'s regions need (``applies(t)`` holds)."""
        return max(g for g, _shape in self.types[t])

    def _forbidden(self, b: int, grade: int):
        """Material of hide ``b`` below ``grade`` (shrunk by tol: touching is fine), prepared."""
        key = (b, grade)
        if key not in self._bad:
            c = self.hides[b]
            bad = Polygon(c.outline).difference(usable_region(c, grade)).buffer(-self.tol, 2)
            self._bad[key] = prep(bad)
        return self._bad[key]

    def ok(self, b: int, t: int, angle: float, mirrored: bool, tx: int, ty: int) -> bool:
        """May type ``t`` lie on hide spec ``b`` at grid translation (tx, ty)?"""
        key = (t, angle, mirrored)
        shapes = self._shapes.get(key)
        if shapes is None:
            shapes = []
            for g, shape in self.types[t]:
                s = affinity.scale(shape, -1.0, 1.0, origin=(0, 0)) if mirrored else shape
                shapes.append((g, affinity.rotate(s, angle, origin=(0, 0)) if angle else s))
            self._shapes[key] = shapes
        x, y = tx / self.scale, ty / self.scale
        for g, shape in shapes:
            if self._forbidden(b, g).intersects(affinity.translate(shape, x, y)):
                return False
        return True


def region_check(parts: Sequence[Part], hides: Sequence[Container], scale: float, tol: float,
                 chord_tol: float) -> Optional[RegionCheck]:
    """A :class:`RegionCheck` for ``parts`` (one type per part, same order) on
    ``hides``, or None when no part has regions."""
    if not hides or not any(p.grade_regions for p in parts):
        return None
    types: List[Optional[List[Tuple[int, BaseGeometry]]]] = []
    rings: List[List[Tuple[int, List[Tuple[float, float]]]]] = []
    for p in parts:
        base = nesting_grade(p)
        strict = [(g, shape) for g, shape, _l in pieces(p, chord_tol) if g > base]
        types.append(strict or None)
        rings.append([(g, [(float(x), float(y)) for x, y in c.points(chord_tol)])
                      for g, c in p.grade_regions if g > base])
    return RegionCheck(types, hides, scale, tol, rings)


def region_grade_levels(parts: Sequence[Part]) -> List[int]:
    """The grades of every part region (the engine builds a hide region for each)."""
    return sorted({g for p in parts for g, _c in p.grade_regions})
