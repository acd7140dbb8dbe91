"""Drawing edges -> segments (and FreeCAD ``Part`` curves for the free-form ones).

Lines and circular arcs become exact :class:`LineSeg` / :class:`ArcSeg`; ellipses
and B-splines are built as FreeCAD curves (``Part.Ellipse`` / ``ArcOfEllipse``,
``Part.BSplineCurve.buildFromPolesMultsKnots``), kept for the face construction
and flattened within the chord tolerance into a :class:`CurveSeg`.  The reverse
direction (segment -> ``Part.Edge`` with end points pinned to graph nodes) is
here too.  All lengths mm, angles degrees (ellipse parameters radians as in DXF).
"""

from __future__ import annotations

import math
from typing import List, Optional, Sequence, Tuple

import FreeCAD
import Part

from ..errors import InputError
from ..geometry import ArcSeg, CurveSeg, LineSeg, Point, Segment
from ..model import ArcEdge, EllipseEdge, LineEdge, SplineEdge

V = FreeCAD.Vector


def describe(edge) -> str:
    """Where an edge came from, for messages: type, handle, layer, block."""
    src = edge.src
    parts = [src.dxftype or type(edge).__name__]
    if src.handle:
        parts.append(f"handle {src.handle}")
    parts.append(f"layer {src.layer!r}")
    if src.block:
        parts.append(f"block {src.block!r}")
    return ", ".join(parts)


def unique_knots(knots: Sequence[float], tol: float = 1e-9) -> Tuple[List[float], List[int]]:
    """Full knot vector (with repeats) -> (distinct knots, multiplicities)."""
    uk: List[float] = []
    mults: List[int] = []
    for k in knots:
        if uk and abs(k - uk[-1]) <= tol * max(1.0, abs(k)):
            mults[-1] += 1
        else:
            uk.append(float(k))
            mults.append(1)
    return uk, mults


def spline_curve(edge: SplineEdge) -> "Part.BSplineCurve":
    """FreeCAD B-spline of a drawing spline (poles, full knot vector, weights)."""
    n, p = len(edge.poles), edge.degree
    if n < 2 or p < 1:
        raise InputError(f"spline with {n} poles and degree {p} cannot be built", describe(edge))
    uk, mults = unique_knots(edge.knots)
    if sum(mults) != n + p + 1 or len(uk) < 2:
        raise InputError(f"spline knot vector of {len(edge.knots)} values does not fit "
                         f"{n} poles of degree {p}", describe(edge))
    # OCC accepts end multiplicities up to degree + 1 only.
    mults[0] = min(mults[0], p + 1)
    mults[-1] = min(mults[-1], p + 1)
    if sum(mults) != n + p + 1:
        raise InputError("spline end knots repeated more than degree + 1 times", describe(edge))
    weights = list(edge.weights) if edge.weights and len(edge.weights) == n else [1.0] * n
    if not all(w > 0 and math.isfinite(w) for w in weights):
        raise InputError("spline weights must be positive finite numbers", describe(edge))
    if not all(math.isfinite(k) for k in uk) or any(b <= a for a, b in zip(uk, uk[1:])):
        raise InputError("spline knots must be finite and non-decreasing", describe(edge))
    curve = Part.BSplineCurve()
    try:
        curve.buildFromPolesMultsKnots([V(x, y, 0) for x, y in edge.poles], mults, uk, False, p,
                                       weights)
    except Exception as exc:   # Part.OCCError and friends: a spline OCC cannot build
        raise InputError(f"spline cannot be built ({type(exc).__name__}: {exc})",
                         describe(edge)) from exc
    return curve


def ellipse_edge(edge: EllipseEdge) -> "Part.Edge":
    """FreeCAD edge of a drawing ellipse (arc)."""
    cx, cy = edge.center
    mx, my = edge.major_axis
    a = math.hypot(mx, my)
    if a <= 0 or not 0 < edge.ratio <= 1.0 + 1e-9:
        raise InputError(f"ellipse with major axis {a} and ratio {edge.ratio} cannot be built",
                         describe(edge))
    b = a * min(edge.ratio, 1.0)
    s1 = V(cx + mx, cy + my, 0)
    s2 = V(cx - my / a * b, cy + mx / a * b, 0)
    ell = Part.Ellipse(s1, s2, V(cx, cy, 0))
    u0, u1 = edge.start_param, edge.end_param
    while u1 <= u0:
        u1 += 2 * math.pi
    if abs(u1 - u0 - 2 * math.pi) < 1e-9:
        return ell.toShape()
    return Part.ArcOfEllipse(ell, u0, u1).toShape()


def flatten(edge: "Part.Edge", chord_tol: float, kind: str) -> CurveSeg:
    """Polyline of a FreeCAD edge in its parameter direction within ``chord_tol`` mm."""
    pts = edge.discretize(Deflection=chord_tol)
    if len(pts) < 2:
        pts = [edge.valueAt(edge.FirstParameter), edge.valueAt(edge.LastParameter)]
    xy = tuple((p.x, p.y) for p in pts)
    if not all(math.isfinite(v) for p in xy for v in p):
        raise InputError(f"{kind} evaluates to points that are not finite (degenerate knots "
                         f"or weights)")
    return CurveSeg(xy, kind)


def to_segment(edge, chord_tol: float) -> Tuple[Segment, Optional["Part.Edge"]]:
    """Drawing edge -> (segment in the drawing's direction, FreeCAD edge or None).

    The FreeCAD edge is only returned for ellipses and splines (lines and arcs are
    rebuilt exactly from their segments when needed)."""
    if isinstance(edge, LineEdge):
        return LineSeg(tuple(edge.start), tuple(edge.end)), None
    if isinstance(edge, ArcEdge):
        if edge.radius <= 0:
            raise InputError(f"arc with radius {edge.radius}", describe(edge))
        sweep = max(-360.0, min(360.0, edge.sweep))
        return ArcSeg(tuple(edge.center), edge.radius, edge.start_angle, sweep), None
    try:
        if isinstance(edge, EllipseEdge):
            pe = ellipse_edge(edge)
            return flatten(pe, chord_tol, "ellipse"), pe
        if isinstance(edge, SplineEdge):
            pe = spline_curve(edge).toShape()
            return flatten(pe, chord_tol, "spline"), pe
    except InputError:
        raise
    except Exception as exc:   # OCC failures building or flattening a free-form curve
        raise InputError(f"curve cannot be built ({type(exc).__name__}: {exc})",
                         describe(edge)) from exc
    raise InputError(f"unknown edge type {type(edge).__name__}", describe(edge))


def segment_edges(seg: Segment, a: Point, b: Point,
                  curve: Optional["Part.Edge"] = None) -> List["Part.Edge"]:
    """FreeCAD edge(s) following ``seg`` but starting at ``a`` and ending at ``b``
    (graph node positions, within the join tolerance of the segment ends).

    Lines and arcs are rebuilt through the node positions so consecutive edges
    share exact vertices; a free-form curve keeps its FreeCAD curve when that
    already ends at the nodes, otherwise its flattened polyline (pinned to the
    nodes) is used."""
    if isinstance(seg, LineSeg):
        return [Part.LineSegment(V(a[0], a[1], 0), V(b[0], b[1], 0)).toShape()]
    if isinstance(seg, ArcSeg):
        if abs(abs(seg.sweep) - 360.0) < 1e-9:
            return [Part.makeCircle(seg.radius, V(seg.center[0], seg.center[1], 0))]
        m = seg.point_at(seg.length / 2)
        return [Part.Arc(V(a[0], a[1], 0), V(m[0], m[1], 0), V(b[0], b[1], 0)).toShape()]
    if curve is not None and _ends_at(curve, a, b):
        return [curve]
    pts = list(seg.points())
    pts[0], pts[-1] = a, b
    return list(Part.makePolygon([V(x, y, 0) for x, y in pts]).Edges)


def _ends_at(edge: "Part.Edge", a: Point, b: Point, tol: float = 1e-7) -> bool:
    """True if ``edge`` runs between ``a`` and ``b`` (either way) within ``tol`` mm."""
    p = edge.valueAt(edge.FirstParameter)
    q = edge.valueAt(edge.LastParameter)
    d = lambda u, v: math.hypot(u.x - v[0], u.y - v[1])  # noqa: E731
    return (d(p, a) <= tol and d(q, b) <= tol) or (d(p, b) <= tol and d(q, a) <= tol)
