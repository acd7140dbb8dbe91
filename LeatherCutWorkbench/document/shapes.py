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
    """A closed wire of the contour (so it can be filled), else a compound of
    its edges.

    Arc end points computed from centre and angles miss the next segment's
    start by up to ~1e-5 mm, more than OCC's 1e-7 mm confusion tolerance, and
    a wire joined across such gaps can give an invalid face; so the loop is
    built with consecutive segments meeting at one shared node each."""
    try:
        wire = Part.Wire(_closed_loop_edges(contour.segments))
        if wire.isClosed():
            return wire
    except (Part.OCCError, ValueError):
        pass
    edges = path_edges(contour.segments)
    try:
        return Part.Wire(edges)
    except Part.OCCError:
        return compound(edges)


#: largest end-to-start distance (mm) bridged by :func:`_closed_loop_edges`
#: (recognition joins within its join tolerance, 0.01 mm by default)
LOOP_SNAP_TOL = 0.01


def _closed_loop_edges(segments: Sequence[Segment]) -> List[Part.Edge]:
    """Edges of a closed loop whose consecutive segments meet at one node each:
    the node is the midpoint of one segment's end and the next one's start;
    lines run between nodes, arcs pass through their own midpoint, flattened
    curves keep their inner points, a lone full circle stays a circle.
    Raises ValueError for a gap over :data:`LOOP_SNAP_TOL`."""
    segs = [s for s in segments if _seg_len(s) > _MIN_LEN]
    if len(segs) == 1 and isinstance(segs[0], ArcSeg) and abs(segs[0].sweep) >= 360.0 - 1e-9:
        return segment_edges(segs[0])
    n = len(segs)
    nodes = []
    for i in range(n):
        a, b = segs[i].end, segs[(i + 1) % n].start
        if math.dist(a, b) > LOOP_SNAP_TOL:
            raise ValueError("gap in the loop")
        nodes.append(((a[0] + b[0]) / 2.0, (a[1] + b[1]) / 2.0))
    out: List[Part.Edge] = []
    for i, seg in enumerate(segs):
        p0, p1 = nodes[i - 1], nodes[i]
        if math.dist(p0, p1) <= _MIN_LEN:
            continue            # shorter than OCC can represent: the nodes coincide
        if isinstance(seg, ArcSeg):
            mid = math.radians(seg.start_angle + seg.sweep / 2.0)
            pm = (seg.center[0] + seg.radius * math.cos(mid), seg.center[1] + seg.radius * math.sin(mid))
            out.append(Part.Arc(_v(p0), _v(pm), _v(p1)).toShape())
        elif isinstance(seg, CurveSeg):
            inner = [p for p in seg.pts[1:-1]
                     if math.dist(p, p0) > _MIN_LEN and math.dist(p, p1) > _MIN_LEN]
            out.extend(Part.makePolygon([_v(p) for p in [p0] + inner + [p1]]).Edges)
        else:
            out.append(Part.LineSegment(_v(p0), _v(p1)).toShape())
    return out


def _seg_len(seg: Segment) -> float:
    if isinstance(seg, ArcSeg):
        return abs(math.radians(seg.sweep)) * seg.radius
    if isinstance(seg, CurveSeg):
        return sum(math.dist(a, b) for a, b in zip(seg.pts, seg.pts[1:]))
    return math.dist(seg.start, seg.end)


def marker_points(points: Sequence[Point]) -> Part.Shape:
    """A compound of vertices (entry points, marks)."""
    return Part.Compound([Part.Vertex(_v(p)) for p in points])
