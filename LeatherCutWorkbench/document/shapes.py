"""Convert the LeatherCut job model into FreeCAD ``Part`` shapes for display.

Everything is drawn in the XY plane at Z = 0 (mm).  Arcs stay true arcs,
splines true B-splines; flattened curves (``CurveSeg``) become polylines.
This module imports ``Part`` but no GUI module.
"""

from __future__ import annotations

import math
from typing import Iterable, List, Optional, Sequence

import FreeCAD
import Part

from ..core import model
from ..core.geometry import ArcSeg, CurveSeg, LineSeg, Point, Segment

V = FreeCAD.Vector
_MIN_LEN = 1e-7


def _v(p: Point) -> "FreeCAD.Vector":
    return V(float(p[0]), float(p[1]), 0.0)


def _arc(center: Point, radius: float, start_deg: float, sweep_deg: float) -> Optional[Part.Edge]:
    if radius <= _MIN_LEN or abs(sweep_deg) <= 1e-9:
        return None
    circle = Part.Circle(_v(center), V(0, 0, 1), float(radius))
    if abs(sweep_deg) >= 360.0 - 1e-9:
        return circle.toShape()
    a0 = math.radians(start_deg if sweep_deg > 0 else start_deg + sweep_deg)
    return Part.ArcOfCircle(circle, a0, a0 + math.radians(abs(sweep_deg))).toShape()


def segment_edges(seg: Segment) -> List[Part.Edge]:
    """Part edges of one path segment (a flattened curve gives several)."""
    if isinstance(seg, LineSeg):
        if math.dist(seg.start, seg.end) <= _MIN_LEN:
            return []
        return [Part.LineSegment(_v(seg.start), _v(seg.end)).toShape()]
    if isinstance(seg, ArcSeg):
        e = _arc(seg.center, seg.radius, seg.start_angle, seg.sweep)
        return [e] if e is not None else []
    if isinstance(seg, CurveSeg):
        pts = [p for i, p in enumerate(seg.pts) if i == 0 or math.dist(p, seg.pts[i - 1]) > _MIN_LEN]
        if len(pts) < 2:
            return []
        return list(Part.makePolygon([_v(p) for p in pts]).Edges)
    raise TypeError(f"unknown segment type {type(seg).__name__}")


def path_edges(segments: Iterable[Segment]) -> List[Part.Edge]:
    out: List[Part.Edge] = []
    for s in segments:
        out.extend(segment_edges(s))
    return out


def _knots_mults(knots: Sequence[float]):
    uniq: List[float] = []
    mults: List[int] = []
    for k in knots:
        if uniq and abs(k - uniq[-1]) <= 1e-12:
            mults[-1] += 1
        else:
            uniq.append(float(k))
            mults.append(1)
    return uniq, mults


def drawing_edge(edge) -> Optional[Part.Edge]:
    """Part edge of one imported drawing edge (line, arc, ellipse, spline)."""
    if isinstance(edge, model.LineEdge):
        if math.dist(edge.start, edge.end) <= _MIN_LEN:
            return None
        return Part.LineSegment(_v(edge.start), _v(edge.end)).toShape()
    if isinstance(edge, model.ArcEdge):
        return _arc(edge.center, edge.radius, edge.start_angle, edge.sweep)
    if isinstance(edge, model.EllipseEdge):
        mx, my = edge.major_axis
        a = math.hypot(mx, my)
        b = a * edge.ratio
        if a <= _MIN_LEN or b <= _MIN_LEN:
            return None
        c = _v(edge.center)
        ell = Part.Ellipse(c + V(mx, my, 0), c + V(-my, mx, 0) * edge.ratio, c)
        t0, t1 = edge.start_param, edge.end_param
        while t1 <= t0:
            t1 += 2 * math.pi
        if t1 - t0 >= 2 * math.pi - 1e-9:
            return ell.toShape()
        return Part.ArcOfEllipse(ell, t0, t1).toShape()
    if isinstance(edge, model.SplineEdge):
        if len(edge.poles) < 2:
            return None
        knots, mults = _knots_mults(edge.knots)
        bs = Part.BSplineCurve()
        weights = [float(w) for w in edge.weights] if edge.weights else [1.0] * len(edge.poles)
        bs.buildFromPolesMultsKnots([_v(p) for p in edge.poles], mults, knots, False,
                                    int(edge.degree), weights)
        return bs.toShape()
    return None


def compound(edges: Sequence[Part.Shape]) -> Part.Shape:
    """A compound of the edges (an empty compound when there are none)."""
    return Part.Compound(list(edges))


def contour_shape(contour: model.Contour) -> Part.Shape:
    """A closed wire of the contour when its edges connect, else a compound."""
    edges = path_edges(contour.segments)
    try:
        return Part.Wire(edges)
    except Part.OCCError:
        return compound(edges)


def marker_points(points: Sequence[Point]) -> Part.Shape:
    """A compound of vertices (entry points, marks)."""
    return Part.Compound([Part.Vertex(_v(p)) for p in points])
