"""The kerf check: the band a torch removes, traced back from the written
G-code, against the drawn parts.

``swept_band`` buffers the traced centre line of every cutting move by half
the kerf (shapely, 32 segments per quarter circle).  ``kerf_deviation``
measures, over the drawn outlines of the parts:

* ``penetration``: how deep (mm) the band reaches into any part's material;
* ``gap``: the largest distance (mm) from a point of a drawn outline to the
  band, over the points a round tool of the kerf's width can reach at all
  (the inside corners of the scrap, e.g. the corners of a square hole, keep a
  fillet of half the kerf with any round tool; those points are counted
  apart in ``unreachable``).
"""

import math

import numpy as np
import shapely
from shapely.geometry import LineString, Polygon
from shapely.ops import unary_union

from LeatherCutWorkbench.post.gcode_reader import interpreter_for, traced_cuts
from LeatherCutWorkbench.core.geometry import path_points

SAMPLE_STEP = 0.25      # mm between checked outline points
MAX_SAMPLES = 4000      # per outline (long outlines are sampled more coarsely)


def traced_moves(text, profile):
    it = interpreter_for(profile)
    for n, line in enumerate(text.splitlines(), 1):
        it.execute(line, n)
    cuts, bad = traced_cuts(it.moves, profile)
    assert not bad, "rapid with the tool down"
    return cuts


def move_points(m, chord=0.001):
    a = (m.start["X"], m.start["Y"])
    b = (m.end["X"], m.end["Y"])
    if m.kind != "arc":
        return [a, b]
    c = m.center
    r = math.dist(c, a)
    a0 = math.atan2(a[1] - c[1], a[0] - c[0])
    a1 = math.atan2(b[1] - c[1], b[0] - c[0])
    sweep = (a1 - a0) % (2 * math.pi) if m.ccw else -((a0 - a1) % (2 * math.pi))
    if abs(sweep) < 1e-12:
        sweep = 2 * math.pi if m.ccw else -2 * math.pi
    step = 2 * math.acos(max(-1.0, 1 - chord / r)) if r > chord else math.pi / 2
    n = max(2, int(math.ceil(abs(sweep) / step)))
    return [(c[0] + r * math.cos(a0 + sweep * k / n), c[1] + r * math.sin(a0 + sweep * k / n))
            for k in range(n + 1)]


def swept_band(moves, half_kerf, origin=(0.0, 0.0)):
    lines = []
    for m in moves:
        pts = [(x - origin[0], y - origin[1]) for x, y in move_points(m)]
        if math.dist(pts[0], pts[-1]) > 1e-9 or len(pts) > 2:
            lines.append(LineString(pts))
    return unary_union([ln.buffer(half_kerf, quad_segs=32) for ln in lines])


def _poly(segs):
    p = Polygon(path_points(segs, 0.002))
    return p if p.is_valid else p.buffer(0)


def kerf_deviation(parts, band, half_kerf, tol=0.02):
    """{"penetration", "gap", "unreachable", "points"} over ``parts`` (drawn)."""
    near_band = band.buffer(tol, quad_segs=8)
    shapely.prepare(near_band)
    pen = 0.0
    gap = 0.0
    unreachable = 0
    npts = 0
    for part in parts:
        outer = _poly(part.outer.segments)
        holes = [_poly(h.segments) for h in part.holes]
        mat = outer
        for h in holes:
            mat = mat.difference(h)
        inside = band.intersection(mat.buffer(-1e-4))
        bpts = shapely.get_coordinates(inside.boundary) if not inside.is_empty else []
        if len(bpts):
            depth = shapely.distance(shapely.points(bpts), mat.boundary)
            pen = max(pen, float(depth.max()))
        d = half_kerf
        scrap = [(outer.buffer(2 * d + 1.0).difference(outer), outer.exterior)]
        scrap += [(h, h.exterior) for h in holes]
        for region, ring in scrap:
            reach = region.buffer(-d, quad_segs=32).buffer(d, quad_segs=32)
            line = LineString(ring.coords)
            n = min(MAX_SAMPLES, max(8, int(line.length / SAMPLE_STEP)))
            pts = shapely.points([line.interpolate(k / n, normalized=True).coords[0]
                                  for k in range(n)])
            npts += n
            reachable = shapely.distance(pts, reach) <= 1e-3 + tol / 4
            unreachable += int((~reachable).sum())
            # exact distances on every 8th point and on every point farther
            # than the tolerance from the band (the prepared test is fast)
            far = ~shapely.intersects(near_band, pts)
            pick = reachable & (far | (np.arange(n) % 8 == 0))
            if pick.any():
                gap = max(gap, float(np.max(shapely.distance(pts[pick], band))))
    return {"penetration": pen, "gap": gap, "unreachable": unreachable, "points": npts}
