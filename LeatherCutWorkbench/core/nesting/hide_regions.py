"""A hide's usable regions in grid units, built the first time the fill opens it.

Per part grade the bottom-left fill needs the material that grade may use
after the margins (:func:`containers.shrink_for_margin`), as grid rings, the
area of the largest such region (the fill's size prune) and a coarse subset
of it for fills under time pressure.  On Baldacci Test10 (ten hides of
~290 vertices, ~45 holes and ~35 zones each, five grades) that takes
0.1-0.15 s per hide (x2 loaded), and a job rarely opens every hide: the
first fill of Test10 uses five.  :class:`HideRegions` is therefore the
recipe, picklable so the worker processes receive it, and
:meth:`HideRegions.build` runs it when :meth:`blf.BinSpec.ready` is first
called for that hide -- the regions are the same as built up front, only
later and only for the hides the search tries.

Units: the container in mm, ``scale`` grid units per mm; rings are integer
grid paths, areas grid units^2.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Dict, List, Sequence, Tuple

import numpy as np
import pyclipper

from ..model import Container
from .containers import polygons_of, shrink_for_margin, zone_pieces
from .shapes import IntPath, convex_hull, to_grid

#: per region key: (outer rings, obstacle rings) in grid units
Regions = Dict[int, Tuple[List[IntPath], List[IntPath]]]


@dataclass
class HideRegions:
    """How to build the regions of hide ``container`` for ``grades``
    (the part grades that may ask for it), after ``margin`` mm, at ``scale``."""

    container: Container
    grades: Sequence[int]
    margin: float
    scale: float

    def build(self) -> Tuple[Regions, Regions, float]:
        """(regions, coarse regions, material): per grade the (outers,
        obstacles) grid rings of the material it may use, the same with few
        vertices (:func:`coarse_region`; absent for an empty region), and the
        area of the largest region (grid units^2; 0 when every region is empty)."""
        c = self.container
        scale = self.scale
        regions: Regions = {}
        coarse: Regions = {}
        material = 0.0
        xs = [p[0] for p in c.outline]
        ys = [p[1] for p in c.outline]
        tol = 0.004 * max(max(xs) - min(xs), max(ys) - min(ys))
        # finely flattened outlines (edges shorter than 1 % of the hide's size on average)
        # simplified within 0.02 % of its size, inside the material: Baldacci Test3/4/9
        # outlines of 1,100-1,900 vertices left ~400 pocket pieces per hide (inner-fit
        # regions 4.5x slower than at 2 units on these 10,000-unit hides)
        fine = _perimeter(c.outline) < 2.5 * tol * len(c.outline)
        edge_tol = max(0.25, 0.05 * tol) if fine else 0.25
        pieces = zone_pieces(c)                 # once per hide, not per grade
        for g in sorted(set(self.grades)):
            outers, holes, region = shrink_for_margin(c, g, self.margin, simplify=edge_tol,
                                                      pieces=pieces)
            regions[g] = ([to_grid(_arr(o), scale) for o in outers],
                          [to_grid(_arr(r), scale) for r in holes])
            if region is not None:
                material = max(material, region.area * scale * scale)
                coarse[g] = coarse_region(region, tol, scale)
        return regions, coarse, material


def coarse_region(region, tol: float, scale: float) -> Tuple[List[IntPath], List[IntPath]]:
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
