"""A hide's usable regions in grid units, each built the first time the fill needs it.

Per part grade the bottom-left fill needs the material that grade may use
after the margins (:func:`containers.shrink_for_margin`), as grid rings, the
area of the largest such region (the fill's size prune) and a coarse subset
of it for fills under time pressure.  On Baldacci Test10 (ten hides of
~290 vertices, ~45 holes and ~35 zones each, five grades) building all of
them took 0.1-0.15 s per hide (x2 loaded), and a job rarely needs them all:

* a hide the fill never opens is never built (the first fill of Test10 uses
  five of ten);
* grades that may use the same material levels share one region (Test10's
  zones have grades 1-3 on grade-5 hides: grades 4 and 5 both keep off every
  zone);
* the coarse region of a grade is built from its material without the exact
  region (:func:`coarse_region` of the usable region shrunk by the margin),
  and the exact region only when an exact inner-fit region first asks for
  it: a first fill under time pressure (worker 0's, coarse) builds no exact
  region at all.

:class:`HideRegions` is the recipe, picklable so the worker processes
receive it; :class:`blf.BinSpec` asks it for the pieces.  Every region is the
one the eager build gave, only later and only where the search looks.

Units: the container in mm, ``scale`` grid units per mm; rings are integer
grid paths, areas grid units^2.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from typing import Dict, List, Optional, Sequence, Tuple

import numpy as np
import pyclipper

from ..model import Container
from .containers import polygons_of, shrink_for_margin, usable_region, zone_pieces
from .shapes import IntPath, convex_hull, to_grid

#: one region: (outer rings, obstacle rings) in grid units
Region = Tuple[List[IntPath], List[IntPath]]
#: per region key
Regions = Dict[int, Region]


@dataclass
class HideRegions:
    """How to build the regions of hide ``container`` for ``grades``
    (the part grades that may ask for it), after ``margin`` mm, at ``scale``."""

    container: Container
    grades: Sequence[int]
    margin: float
    scale: float
    _pieces: Optional[list] = field(default=None, init=False, repr=False, compare=False)
    _usable: Dict[int, object] = field(default_factory=dict, init=False, repr=False,
                                       compare=False)

    def keys(self) -> Dict[int, int]:
        """Part grade -> region key: the lowest grade that may use the same
        material levels (the hide's base grade and its zones' grades at
        least as good), so equal regions are built once."""
        c = self.container
        levels = sorted({c.base_grade} | {zg for zg, _ in c.zones})
        first: Dict[Tuple[int, ...], int] = {}
        out: Dict[int, int] = {}
        for g in sorted(set(self.grades)):
            allowed = tuple(lv for lv in levels if lv >= g)
            out[g] = first.setdefault(allowed, g)
        return out

    def material(self) -> float:
        """Area (grid units^2) of the largest region, before the margin (an
        upper bound, as the size prune needs): that of the most permissive
        grade, whose material holds every other grade's; 0 when empty."""
        if not self.grades:
            return 0.0
        region = self.usable(min(self.grades))
        return region.area * self.scale * self.scale

    def usable(self, key: int):
        """:func:`containers.usable_region` of grade ``key``, no margins (once
        per key: ``material``, ``coarse`` and ``exact`` all start from it)."""
        hit = self._usable.get(key)
        if hit is None:
            hit = self._usable[key] = usable_region(self.container, key, self.pieces())
        return hit

    def pieces(self):
        """:func:`containers.zone_pieces` of the hide (once)."""
        if self._pieces is None:
            self._pieces = zone_pieces(self.container)
        return self._pieces

    def _tol(self) -> float:
        xs = [p[0] for p in self.container.outline]
        ys = [p[1] for p in self.container.outline]
        return 0.004 * max(max(xs) - min(xs), max(ys) - min(ys))

    def exact(self, key: int) -> Region:
        """The exact region of grade ``key``: (outers, obstacles) grid rings of
        the material it may use after the margins."""
        c = self.container
        tol = self._tol()
        # finely flattened outlines (edges shorter than 1 % of the hide's size on average)
        # simplified within 0.02 % of its size, inside the material: Baldacci Test3/4/9
        # outlines of 1,100-1,900 vertices left ~400 pocket pieces per hide (inner-fit
        # regions 4.5x slower than at 2 units on these 10,000-unit hides)
        fine = _perimeter(c.outline) < 2.5 * tol * len(c.outline)
        edge_tol = max(0.25, 0.05 * tol) if fine else 0.25
        outers, holes, _region = shrink_for_margin(c, key, self.margin, simplify=edge_tol,
                                                   usable=self.usable(key))
        return ([to_grid(_arr(o), self.scale) for o in outers],
                [to_grid(_arr(r), self.scale) for r in holes])

    def coarse(self, key: int) -> Optional[Region]:
        """A subset of the region of grade ``key`` with few vertices
        (:func:`coarse_region` of its material shrunk by the margin, which
        keeps the margin from zone borders too), None when it is empty."""
        region = self.usable(key)
        if self.margin > 0 and not region.is_empty:
            region = region.buffer(-self.margin, 16)
        if region.is_empty:
            return None
        return coarse_region(region, self._tol(), self.scale)


def coarse_region(region, tol: float, scale: float) -> Region:
    """A subset of a hide region (shapely, mm) with few vertices, for inner-fit
    regions under time pressure: shrunk by ``tol`` mm then simplified within
    0.9 ``tol`` (so it stays inside), holes as their convex hulls (which
    contain them); grid rings at ``scale``."""
    small = region.buffer(-tol, 4, join_style=2).simplify(0.9 * tol)
    outers, obstacles = [], []
    for p in polygons_of(small):
        ring = to_grid(_arr(p.exterior.coords[:-1]), scale)
        if len(ring) >= 3:
            outers.append(ring if pyclipper.Orientation(ring) else ring[::-1])
        for r in p.interiors:
            hole = convex_hull(to_grid(_arr(r.coords[:-1]), scale))
            if len(hole) >= 3:
                obstacles.append(hole)
    return outers, obstacles


def _perimeter(ring) -> float:
    return float(sum(math.dist(ring[i - 1], ring[i]) for i in range(len(ring))))


def _arr(ring) -> np.ndarray:
    return np.asarray(ring, dtype=float)
