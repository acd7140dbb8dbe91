"""FreeCAD wires -> plain segments (:mod:`core.geometry`), and path orientation.

Lines become :class:`LineSeg`, circles and circular arcs exact :class:`ArcSeg`,
everything else (ellipse, B-spline, offset curves) a :class:`CurveSeg` flattened
within the chord tolerance.  Segments are chained so each one starts where the
previous ended, whatever the FreeCAD edge orientation flags say.
"""

from __future__ import annotations

import math
from typing import List, Sequence

import Part

from ..geometry import ArcSeg, CurveSeg, LineSeg, Segment, dist


def edge_segment(edge: "Part.Edge", chord_tol: float) -> Segment:
    """One FreeCAD edge -> one segment in the edge's parameter direction."""
    u0, u1 = edge.FirstParameter, edge.LastParameter
    p0 = edge.valueAt(u0)
    p1 = edge.valueAt(u1)
    curve = edge.Curve
    if isinstance(curve, (Part.Line, Part.LineSegment)):
        return LineSeg((p0.x, p0.y), (p1.x, p1.y))
    if isinstance(curve, Part.Circle):
        c = curve.Center
        sweep = math.degrees(u1 - u0)
        if curve.Axis.z < 0:
            sweep = -sweep
        a0 = math.degrees(math.atan2(p0.y - c.y, p0.x - c.x))
        return ArcSeg((c.x, c.y), curve.Radius, a0, sweep)
    kind = "ellipse" if isinstance(curve, Part.Ellipse) else "spline"
    pts = edge.discretize(Deflection=chord_tol)
    return CurveSeg(tuple((p.x, p.y) for p in pts), kind)


def chain(segs: Sequence[Segment]) -> List[Segment]:
    """Flip segments of an ordered sequence so that consecutive ones connect."""
    out: List[Segment] = list(segs)
    if len(out) < 2:
        return out
    a, b = out[0], out[1]
    if min(dist(a.start, b.start), dist(a.start, b.end)) < min(dist(a.end, b.start),
                                                               dist(a.end, b.end)):
        out[0] = a.reversed()
    for i in range(1, len(out)):
        prev_end = out[i - 1].end
        s = out[i]
        if dist(prev_end, s.end) < dist(prev_end, s.start):
            out[i] = s.reversed()
    return out


def signed_path_area(segs: Sequence[Segment]) -> float:
    """Signed area (mm^2, CCW positive) of a closed path: exact for lines and arcs
    (chord shoelace plus circular-segment term), polyline for curves."""
    a = 0.0
    for s in segs:
        if isinstance(s, LineSeg):
            (x0, y0), (x1, y1) = s.start, s.end
            a += x0 * y1 - x1 * y0
        elif isinstance(s, ArcSeg):
            (x0, y0), (x1, y1) = s.start, s.end
            a += x0 * y1 - x1 * y0
            th = math.radians(s.sweep)
            a += s.radius * s.radius * (th - math.sin(th))
        else:
            p = s.pts
            for i in range(len(p) - 1):
                a += p[i][0] * p[i + 1][1] - p[i + 1][0] * p[i][1]
    return a / 2.0


def reverse(segs: Sequence[Segment]) -> List[Segment]:
    return [s.reversed() for s in reversed(segs)]


def orient(segs: Sequence[Segment], ccw: bool) -> List[Segment]:
    """The closed path running counter-clockwise (``ccw``) or clockwise."""
    area = signed_path_area(segs)
    return list(segs) if (area > 0) == ccw else reverse(segs)
