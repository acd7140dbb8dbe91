"""Generated lead-ins and lead-outs on the scrap side of a closed contour.

Units: mm and degrees.  A lead-in ends at the entry point of the (already
compensated and oriented) contour and a lead-out starts there:

* ``line``: a straight line meeting the contour at ``angle`` degrees to its
  tangent (90 = square on), ``length`` mm long;
* ``arc``: a circular arc tangent to the contour at the entry, sweeping
  ``angle`` degrees over ``length`` mm of arc (radius = length / sweep).

Both lie on the scrap side: outside an outer contour, inside a hole.  Whether
a lead is usable is decided by :func:`is_clear` with shapely: the band the tool
removes along it (centre line buffered by half the kerf) must not enter any
part's material (its own included) or a defect of the hide.
"""

from __future__ import annotations

import math
from typing import List, Optional, Sequence, Tuple

from ..core.geometry import ArcSeg, LineSeg, Point, Segment, path_points

#: Material closer than this (mm) to a lead's band counts as touched: the
#: band of a lead meets the contour's own band exactly at the entry.
CLEARANCE_TOL = 0.01
#: Half-width (mm) of the band checked for a tool without kerf (knife, pen):
#: below CLEARANCE_TOL, so a lead ending on the contour does not touch it.
MIN_BAND = 0.005


def frame(tangent_deg: float, scrap_left: bool) -> Tuple[Point, Point]:
    """(unit tangent, unit normal pointing to the scrap side)."""
    a = math.radians(tangent_deg)
    t = (math.cos(a), math.sin(a))
    n = (-t[1], t[0]) if scrap_left else (t[1], -t[0])
    return t, n


def lead_in(entry: Point, tangent_deg: float, scrap_left: bool, shape: str,
            length: float, angle: float) -> List[Segment]:
    """Lead-in segments ending at ``entry`` where the contour leaves in
    direction ``tangent_deg``; ``scrap_left``: the scrap lies left of it."""
    t, n = frame(tangent_deg, scrap_left)
    if shape == "line":
        a = math.radians(angle)
        start = (entry[0] + length * (math.sin(a) * n[0] - math.cos(a) * t[0]),
                 entry[1] + length * (math.sin(a) * n[1] - math.cos(a) * t[1]))
        return [LineSeg(start, entry)]
    r = length / math.radians(angle)
    c = (entry[0] + r * n[0], entry[1] + r * n[1])
    ccw = (entry[0] - c[0]) * t[1] - (entry[1] - c[1]) * t[0] > 0
    sweep = angle if ccw else -angle
    a_end = math.degrees(math.atan2(entry[1] - c[1], entry[0] - c[0]))
    return [ArcSeg(c, r, a_end - sweep, sweep)]


def lead_out(exit_: Point, tangent_deg: float, scrap_left: bool, shape: str,
             length: float, angle: float) -> List[Segment]:
    """Lead-out segments starting at ``exit_`` where the contour arrives in
    direction ``tangent_deg``: the mirror image of :func:`lead_in`."""
    t, n = frame(tangent_deg, scrap_left)
    if shape == "line":
        a = math.radians(angle)
        end = (exit_[0] + length * (math.sin(a) * n[0] + math.cos(a) * t[0]),
               exit_[1] + length * (math.sin(a) * n[1] + math.cos(a) * t[1]))
        return [LineSeg(exit_, end)]
    r = length / math.radians(angle)
    c = (exit_[0] + r * n[0], exit_[1] + r * n[1])
    ccw = (exit_[0] - c[0]) * t[1] - (exit_[1] - c[1]) * t[0] > 0
    a0 = math.degrees(math.atan2(exit_[1] - c[1], exit_[0] - c[0]))
    return [ArcSeg(c, r, a0, angle if ccw else -angle)]


def normal_extent(shape: str, length: float, angle: float) -> float:
    """How far (mm) a lead reaches away from its contour, measured square to it."""
    if shape == "line":
        return length * math.sin(math.radians(min(angle, 90.0)))
    if shape == "arc":
        r = length / math.radians(angle)
        return r * (1.0 - math.cos(math.radians(angle))) if angle <= 90.0 else \
            r * (1.0 + math.sin(math.radians(angle - 90.0)))
    return 0.0


class Obstacles:
    """Part material and defects a lead's band must not enter (shapely
    polygons, indexed by an STRtree)."""

    def __init__(self, polygons: Sequence):
        from shapely import STRtree
        from shapely.prepared import prep

        self.polys = [p.buffer(-CLEARANCE_TOL) for p in polygons]
        self.polys = [p for p in self.polys if not p.is_empty]
        self.prepared = [prep(p) for p in self.polys]
        self.tree = STRtree(self.polys) if self.polys else None

    def hits(self, geom) -> Optional[int]:
        """Index of an obstacle ``geom`` intersects, or None."""
        if self.tree is None:
            return None
        for k in self.tree.query(geom):
            if self.prepared[int(k)].intersects(geom):
                return int(k)
        return None


def band(segments: Sequence[Segment], half_width: float):
    """The region (shapely) the tool removes along ``segments``."""
    from shapely.geometry import LineString

    pts = path_points(segments, 0.01)
    return LineString(pts).buffer(max(half_width, MIN_BAND), quad_segs=8)


def is_clear(segments: Sequence[Segment], half_width: float, obstacles: Obstacles) -> bool:
    """Whether the band of a lead touches no obstacle."""
    return obstacles.hits(band(segments, half_width)) is None
