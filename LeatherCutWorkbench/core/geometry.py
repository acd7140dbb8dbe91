"""Plain 2-D path segments shared by every stage after import.

All coordinates are millimetres, all angles degrees (counter-clockwise positive,
0 = +X).  Nothing here imports FreeCAD: recognition converts FreeCAD edges into
these segments so nesting, planning and post-processing run without FreeCAD.

Three segment kinds cover every contour a cutter follows:

* :class:`LineSeg`  -- a straight cut,
* :class:`ArcSeg`   -- a circular arc (kept exact so posts can emit G2/G3),
* :class:`CurveSeg` -- any other curve (ellipse, B-spline) already flattened to a
  polyline within the recognition chord tolerance.

Every segment is directed: ``start`` -> ``end``.  A path is a list of segments in
which each ``end`` coincides with the next ``start`` (within the join tolerance).
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Iterable, List, Sequence, Tuple, Union

Point = Tuple[float, float]

#: Default chord tolerance (mm) used when arcs are flattened to polylines.
DEFAULT_CHORD_TOL = 0.01


def dist(a: Point, b: Point) -> float:
    """Euclidean distance between two points in mm."""
    return math.hypot(b[0] - a[0], b[1] - a[1])


def heading(a: Point, b: Point) -> float:
    """Direction from ``a`` to ``b`` in degrees, in (-180, 180]."""
    return math.degrees(math.atan2(b[1] - a[1], b[0] - a[0]))


def turn_angle(h_in: float, h_out: float) -> float:
    """Absolute change of heading in degrees, in [0, 180]."""
    d = (h_out - h_in + 180.0) % 360.0 - 180.0
    return abs(d) if d != -180.0 else 180.0


@dataclass(frozen=True)
class LineSeg:
    """Straight segment from ``start`` to ``end`` (mm)."""

    start: Point
    end: Point

    @property
    def length(self) -> float:
        return dist(self.start, self.end)

    def reversed(self) -> "LineSeg":
        return LineSeg(self.end, self.start)

    def points(self, chord_tol: float = DEFAULT_CHORD_TOL) -> List[Point]:
        """Polyline from start to end inclusive."""
        return [self.start, self.end]

    def start_heading(self) -> float:
        return heading(self.start, self.end)

    def end_heading(self) -> float:
        return heading(self.start, self.end)

    def point_at(self, s: float) -> Point:
        """Point at arc length ``s`` (mm) from the start, clamped to the segment."""
        n = self.length
        t = 0.0 if n == 0 else min(max(s / n, 0.0), 1.0)
        return (self.start[0] + t * (self.end[0] - self.start[0]),
                self.start[1] + t * (self.end[1] - self.start[1]))

    def split_at(self, s: float) -> Tuple["LineSeg", "LineSeg"]:
        p = self.point_at(s)
        return LineSeg(self.start, p), LineSeg(p, self.end)

    def transformed(self, xf: "Transform2D") -> "LineSeg":
        return LineSeg(xf.apply(self.start), xf.apply(self.end))


@dataclass(frozen=True)
class ArcSeg:
    """Circular arc: ``center`` (mm), ``radius`` (mm), ``start_angle`` and signed
    ``sweep`` in degrees (positive = counter-clockwise).  |sweep| <= 360."""

    center: Point
    radius: float
    start_angle: float
    sweep: float

    def _pt(self, ang_deg: float) -> Point:
        a = math.radians(ang_deg)
        return (self.center[0] + self.radius * math.cos(a),
                self.center[1] + self.radius * math.sin(a))

    @property
    def start(self) -> Point:
        return self._pt(self.start_angle)

    @property
    def end(self) -> Point:
        return self._pt(self.start_angle + self.sweep)

    @property
    def ccw(self) -> bool:
        return self.sweep > 0

    @property
    def length(self) -> float:
        return abs(math.radians(self.sweep)) * self.radius

    def reversed(self) -> "ArcSeg":
        return ArcSeg(self.center, self.radius, self.start_angle + self.sweep, -self.sweep)

    def points(self, chord_tol: float = DEFAULT_CHORD_TOL) -> List[Point]:
        """Polyline whose chords deviate at most ``chord_tol`` mm from the arc."""
        r = self.radius
        if r <= chord_tol:
            n = 1
        else:
            step = 2.0 * math.degrees(math.acos(max(-1.0, 1.0 - chord_tol / r)))
            n = max(1, int(math.ceil(abs(self.sweep) / max(step, 1e-6))))
        return [self._pt(self.start_angle + self.sweep * i / n) for i in range(n + 1)]

    def start_heading(self) -> float:
        return self.start_angle + (90.0 if self.sweep > 0 else -90.0)

    def end_heading(self) -> float:
        return self.start_angle + self.sweep + (90.0 if self.sweep > 0 else -90.0)

    def point_at(self, s: float) -> Point:
        n = self.length
        t = 0.0 if n == 0 else min(max(s / n, 0.0), 1.0)
        return self._pt(self.start_angle + t * self.sweep)

    def split_at(self, s: float) -> Tuple["ArcSeg", "ArcSeg"]:
        n = self.length
        t = 0.0 if n == 0 else min(max(s / n, 0.0), 1.0)
        a = self.sweep * t
        return (ArcSeg(self.center, self.radius, self.start_angle, a),
                ArcSeg(self.center, self.radius, self.start_angle + a, self.sweep - a))

    def transformed(self, xf: "Transform2D") -> "ArcSeg":
        c = xf.apply(self.center)
        sa = self.start_angle
        sw = self.sweep
        if xf.mirrored:
            sa = 180.0 - sa
            sw = -sw
        return ArcSeg(c, self.radius * xf.scale, sa + xf.angle, sw)


@dataclass(frozen=True)
class CurveSeg:
    """Free-form curve (ellipse, spline) flattened to a polyline (mm).

    ``pts`` holds at least two points; ``kind`` names the source curve so a writer
    can say what it approximated."""

    pts: Tuple[Point, ...]
    kind: str = "curve"

    @property
    def start(self) -> Point:
        return self.pts[0]

    @property
    def end(self) -> Point:
        return self.pts[-1]

    @property
    def length(self) -> float:
        return sum(dist(a, b) for a, b in zip(self.pts, self.pts[1:]))

    def reversed(self) -> "CurveSeg":
        return CurveSeg(tuple(reversed(self.pts)), self.kind)

    def points(self, chord_tol: float = DEFAULT_CHORD_TOL) -> List[Point]:
        return list(self.pts)

    def start_heading(self) -> float:
        return heading(self.pts[0], self.pts[1])

    def end_heading(self) -> float:
        return heading(self.pts[-2], self.pts[-1])

    def point_at(self, s: float) -> Point:
        return self.split_at(s)[0].end

    def split_at(self, s: float) -> Tuple["CurveSeg", "CurveSeg"]:
        acc = 0.0
        for i in range(len(self.pts) - 1):
            a, b = self.pts[i], self.pts[i + 1]
            d = dist(a, b)
            if acc + d >= s:
                t = 0.0 if d == 0 else (s - acc) / d
                p = (a[0] + t * (b[0] - a[0]), a[1] + t * (b[1] - a[1]))
                return (CurveSeg(self.pts[: i + 1] + (p,), self.kind),
                        CurveSeg((p,) + self.pts[i + 1:], self.kind))
            acc += d
        return self, CurveSeg((self.end, self.end), self.kind)

    def transformed(self, xf: "Transform2D") -> "CurveSeg":
        return CurveSeg(tuple(xf.apply(p) for p in self.pts), self.kind)


Segment = Union[LineSeg, ArcSeg, CurveSeg]


@dataclass(frozen=True)
class Transform2D:
    """Similarity transform: optional mirror about the Y axis (x -> -x), then
    uniform ``scale``, then rotation by ``angle`` degrees about the origin, then
    translation by (``dx``, ``dy``) mm.  This is the placement transform the
    nesting stage returns for each part copy."""

    dx: float = 0.0
    dy: float = 0.0
    angle: float = 0.0
    mirrored: bool = False
    scale: float = 1.0

    def apply(self, p: Point) -> Point:
        x, y = p
        if self.mirrored:
            x = -x
        x *= self.scale
        y *= self.scale
        a = math.radians(self.angle)
        c, s = math.cos(a), math.sin(a)
        return (c * x - s * y + self.dx, s * x + c * y + self.dy)


def path_points(segments: Sequence[Segment], chord_tol: float = DEFAULT_CHORD_TOL) -> List[Point]:
    """Flatten a connected path to one polyline (shared joints not repeated)."""
    out: List[Point] = []
    for seg in segments:
        pts = seg.points(chord_tol)
        out.extend(pts if not out else pts[1:])
    return out


def path_length(segments: Iterable[Segment]) -> float:
    """Total length of a path in mm."""
    return sum(s.length for s in segments)


def signed_area(pts: Sequence[Point]) -> float:
    """Shoelace area in mm^2 of a closed polyline (positive = counter-clockwise)."""
    n = len(pts)
    if n < 3:
        return 0.0
    a = 0.0
    for i in range(n):
        x0, y0 = pts[i]
        x1, y1 = pts[(i + 1) % n]
        a += x0 * y1 - x1 * y0
    return a / 2.0


def bbox(pts: Iterable[Point]) -> Tuple[float, float, float, float]:
    """Axis-aligned bounding box (xmin, ymin, xmax, ymax) in mm."""
    xs, ys = zip(*pts)
    return (min(xs), min(ys), max(xs), max(ys))


def reverse_path(segments: Sequence[Segment]) -> List[Segment]:
    """The same path traversed the other way."""
    return [s.reversed() for s in reversed(segments)]


def rotate_closed_path(segments: Sequence[Segment], s: float) -> List[Segment]:
    """Re-start a closed path at arc length ``s`` mm from its current start.

    The segment containing the new start is split there; the result begins and
    ends at the new start point (the entry = exit of a closed contour)."""
    total = path_length(segments)
    if total <= 0:
        return list(segments)
    s = s % total
    acc = 0.0
    for i, seg in enumerate(segments):
        if acc + seg.length > s or i == len(segments) - 1:
            local = s - acc
            if local <= 1e-9:
                return list(segments[i:]) + list(segments[:i])
            head, tail = seg.split_at(local)
            return [tail] + list(segments[i + 1:]) + list(segments[:i]) + [head]
        acc += seg.length
    return list(segments)
