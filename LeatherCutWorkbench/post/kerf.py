"""Kerf compensation: a closed contour of lines and arcs offset by a distance,
arcs kept as exact arcs.

Units: mm and degrees.  A path is offset to its *left* by ``d`` (negative =
to the right): lines become parallel lines, an arc becomes the concentric arc
of radius ``r -/+ d`` (counter-clockwise / clockwise arcs), flattened curves
(:class:`CurveSeg`) are offset chord by chord.  Where the offset pieces leave a
gap (a corner turning away from the offset side) the corner is joined by an arc
of radius ``|d|`` about the drawn vertex (``"round"``) or by the two tangents
extended to their intersection (``"extended"``, mitred; corners sharper than
:data:`MITRE_LIMIT` fall back to round).  Where the pieces overlap they are
trimmed at their intersection; a piece the trimming consumes is removed and its
neighbours are joined again.

Written by hand: shapely and pyclipper offset only polygons (every arc becomes
chords and G2/G3 output would be lost).  Their result is used as the reference
instead: :func:`offset_closed` checks its own path against shapely's buffer of
the flattened contour and raises :class:`OffsetError` rather than return a path
that gouges the part, crosses itself, or hides a lost feature (the contour
vanishes or falls apart into several pieces under the offset).
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import List, Optional, Sequence, Tuple

from ..core.geometry import ArcSeg, CurveSeg, LineSeg, Point, Segment, path_points

#: Joins sharper than this mitre ratio (mitre length / offset) are rounded.
MITRE_LIMIT = 4.0
#: Convex turns below this angle (degrees) are mitred even in "round" mode:
#: the mitre then deviates less than 1.6e-4 * d from the round join, and the
#: chords of a flattened curve do not each get a tiny arc.
SMOOTH_TURN = 2.0
#: Tolerance (mm) of the checks against shapely's buffer.
CHECK_TOL = 0.005
CORNERS = ("round", "extended")
#: Drawn joints closer than this (mm) count as one corner.
JOIN_TOL = 1e-3


class OffsetError(ValueError):
    """The contour cannot be offset by this distance.  ``reason`` is
    ``"vanishes"``, ``"splits"`` or ``"invalid"``; ``where`` a point near the
    problem (mm) when known."""

    def __init__(self, reason: str, message: str, where: Optional[Point] = None):
        super().__init__(message)
        self.reason = reason
        self.where = where


@dataclass
class _Piece:
    """One offset piece: a line (``center`` None) or an arc of ``radius`` about
    ``center`` running ``ccw``; ``p0``/``p1`` its current end points; ``u`` the
    line direction; ``vertex`` the drawn point its end was offset from."""

    p0: Point
    p1: Point
    vertex: Point
    vstart: Point
    u: Point = (0.0, 0.0)
    center: Optional[Point] = None
    radius: float = 0.0
    ccw: bool = True
    sweep0: float = 0.0          # |sweep| of the untrimmed arc, degrees
    join: bool = False           # a corner arc (it may be trimmed, never extended)
    a0: float = 0.0              # untrimmed start angle of the arc, degrees

    def tangent_end(self) -> Point:
        return self.u if self.center is None else _arc_tangent(self, self.p1)

    def tangent_start(self) -> Point:
        return self.u if self.center is None else _arc_tangent(self, self.p0)


def _arc_tangent(p: _Piece, at: Point) -> Point:
    rx, ry = at[0] - p.center[0], at[1] - p.center[1]
    n = math.hypot(rx, ry) or 1.0
    return (-ry / n, rx / n) if p.ccw else (ry / n, -rx / n)


def _ang(c: Point, p: Point) -> float:
    return math.degrees(math.atan2(p[1] - c[1], p[0] - c[0]))


def _wrap(a: float) -> float:
    return (a + 180.0) % 360.0 - 180.0


def _arc_sweep(p: _Piece) -> float:
    """Signed-by-direction sweep (degrees, >0 valid) of the trimmed arc, measured
    from the untrimmed start so a trim past the far end shows up negative."""
    sgn = 1.0 if p.ccw else -1.0
    ds = sgn * _wrap(_ang(p.center, p.p0) - p.a0)
    de = sgn * _wrap(_ang(p.center, p.p1) - (p.a0 + sgn * p.sweep0))
    return p.sweep0 - ds + de


def _length_along(p: _Piece) -> float:
    """Length (mm) of the trimmed piece; negative when trimming consumed it
    (or extended a corner arc past its corner)."""
    if p.center is None:
        return (p.p1[0] - p.p0[0]) * p.u[0] + (p.p1[1] - p.p0[1]) * p.u[1]
    sweep = _arc_sweep(p)
    if p.join and sweep > p.sweep0 + 1e-7:
        return -math.radians(sweep - p.sweep0) * p.radius
    return math.radians(sweep) * p.radius


def _basic(segments: Sequence[Segment]) -> List[Segment]:
    out: List[Segment] = []
    for s in segments:
        if isinstance(s, CurveSeg):
            out.extend(LineSeg(a, b) for a, b in zip(s.pts, s.pts[1:]))
        else:
            out.append(s)
    return [s for s in out if s.length > 1e-9]


def _offset_piece(seg: Segment, d: float) -> Optional[_Piece]:
    if isinstance(seg, LineSeg):
        L = seg.length
        u = ((seg.end[0] - seg.start[0]) / L, (seg.end[1] - seg.start[1]) / L)
        n = (-u[1] * d, u[0] * d)
        return _Piece((seg.start[0] + n[0], seg.start[1] + n[1]),
                      (seg.end[0] + n[0], seg.end[1] + n[1]), seg.end, seg.start, u=u)
    r = seg.radius - d if seg.sweep > 0 else seg.radius + d
    if r <= 1e-6:
        return None                       # the arc shrinks to nothing
    a1 = seg.start_angle + seg.sweep
    c = seg.center
    pt = lambda a: (c[0] + r * math.cos(math.radians(a)), c[1] + r * math.sin(math.radians(a)))  # noqa: E731
    return _Piece(pt(seg.start_angle), pt(a1), seg.end, seg.start, center=c, radius=r,
                  ccw=seg.sweep > 0, sweep0=abs(seg.sweep), a0=seg.start_angle)


def _intersections(a: _Piece, b: _Piece) -> List[Point]:
    """Points where the carriers (infinite line / full circle) of two pieces meet."""
    if a.center is None and b.center is None:
        den = a.u[0] * b.u[1] - a.u[1] * b.u[0]
        if abs(den) < 1e-12:
            return []
        dx, dy = b.p0[0] - a.p0[0], b.p0[1] - a.p0[1]
        t = (dx * b.u[1] - dy * b.u[0]) / den
        return [(a.p0[0] + t * a.u[0], a.p0[1] + t * a.u[1])]
    if a.center is None or b.center is None:
        ln, ci = (a, b) if a.center is None else (b, a)
        fx, fy = ln.p0[0] - ci.center[0], ln.p0[1] - ci.center[1]
        bq = fx * ln.u[0] + fy * ln.u[1]
        cq = fx * fx + fy * fy - ci.radius ** 2
        disc = bq * bq - cq
        if disc < -1e-12:
            return []
        sq = math.sqrt(max(disc, 0.0))
        return [(ln.p0[0] + t * ln.u[0], ln.p0[1] + t * ln.u[1]) for t in (-bq - sq, -bq + sq)]
    (x0, y0), (x1, y1) = a.center, b.center
    dd = math.hypot(x1 - x0, y1 - y0)
    if dd < 1e-12 or dd > a.radius + b.radius + 1e-9 or dd < abs(a.radius - b.radius) - 1e-9:
        return []
    k = (a.radius ** 2 - b.radius ** 2 + dd * dd) / (2 * dd)
    h = math.sqrt(max(a.radius ** 2 - k * k, 0.0))
    mx, my = x0 + k * (x1 - x0) / dd, y0 + k * (y1 - y0) / dd
    ox, oy = -(y1 - y0) / dd * h, (x1 - x0) / dd * h
    return [(mx + ox, my + oy), (mx - ox, my - oy)]


def _cross(a: Point, b: Point) -> float:
    return a[0] * b[1] - a[1] * b[0]


def _dist(a: Point, b: Point) -> float:
    return math.hypot(b[0] - a[0], b[1] - a[1])


def _turn_deg(t_in: Point, t_out: Point) -> float:
    return abs(math.degrees(math.atan2(_cross(t_in, t_out), t_in[0] * t_out[0] + t_in[1] * t_out[1])))


def _with_joins(pieces: List[_Piece], d: float, corner: str) -> List[_Piece]:
    """Insert the corner pieces where neighbours leave a gap on the offset side:
    an arc of radius |d| about the drawn corner, or (``extended``, and turns
    below :data:`SMOOTH_TURN`) the two tangents up to their intersection.
    Joining *before* trimming keeps a corner arc when a short piece next to it
    is consumed by a neighbouring overlap."""
    out: List[_Piece] = []
    n = len(pieces)
    for j, p in enumerate(pieces):
        out.append(p)
        q = pieces[(j + 1) % n]
        if _dist(p.p1, q.p0) < 1e-9:
            continue
        t_in, t_out = p.tangent_end(), q.tangent_start()
        if _cross(t_in, t_out) * d >= 0:
            continue                      # overlap: trimmed later
        turn = _turn_deg(t_in, t_out)
        # the drawn corner: the midpoint of the two drawn ends (drawings join
        # only to within a few microns)
        c = ((p.vertex[0] + q.vstart[0]) / 2.0, (p.vertex[1] + q.vstart[1]) / 2.0)
        mitre_ratio = 1.0 / max(math.cos(math.radians(turn) / 2.0), 1e-9)
        if turn < SMOOTH_TURN or (corner == "extended" and mitre_ratio <= MITRE_LIMIT):
            t = abs(d) * math.tan(math.radians(turn) / 2.0)
            x = (p.p1[0] + t * t_in[0], p.p1[1] + t * t_in[1])
            out.append(_Piece(p.p1, x, c, c, u=t_in))
            out.append(_Piece(x, q.p0, c, c, u=t_out))
        else:
            a0, a1 = _ang(c, p.p1), _ang(c, q.p0)
            sw = _wrap(a1 - a0)
            # the corner arc turns like the drawn corner: clockwise for a left offset
            sw = -((-sw) % 360.0) if d > 0 else sw % 360.0
            out.append(_Piece(p.p1, q.p0, c, c, center=c, radius=abs(d), ccw=d < 0,
                              sweep0=abs(sw), a0=a0, join=True))
    return out


def _trim(pieces: List[_Piece]) -> List[_Piece]:
    """Trim overlapping neighbours at their intersection, dropping pieces the
    trimming consumes (and joining their neighbours again)."""
    orig = [_Piece(**p.__dict__) for p in pieces]
    work = list(range(len(pieces)))
    for _ in range(len(pieces) + 1):
        cur = [_Piece(**orig[i].__dict__) for i in work]
        n = len(cur)
        for j in range(n):
            a, b = cur[j], cur[(j + 1) % n]
            if _dist(a.p1, b.p0) < 1e-9:
                continue
            pts = _intersections(a, b)
            if pts:                       # else: the emitter joins them by a line
                mid = ((a.p1[0] + b.p0[0]) / 2, (a.p1[1] + b.p0[1]) / 2)

                def score(x: Point) -> Tuple[int, float]:
                    # prefer a meeting point that leaves both pieces valid
                    ta, tb = _Piece(**{**a.__dict__, "p1": x}), _Piece(**{**b.__dict__, "p0": x})
                    ok = (_length_along(ta) > 1e-9) + (_length_along(tb) > 1e-9)
                    return (-ok, _dist(x, mid))
                x = min(pts, key=score)
                a.p1 = x
                b.p0 = x
        lengths = [_length_along(p) for p in cur]
        worst = min(range(n), key=lambda k: lengths[k])
        if lengths[worst] > 1e-9 or n <= 2:
            return cur
        del work[worst]
    raise OffsetError("invalid", "offset pieces could not be trimmed")


def _emit(pieces: List[_Piece]) -> List[Segment]:
    out: List[Segment] = []
    n = len(pieces)
    for j, p in enumerate(pieces):
        if p.center is None:
            if _dist(p.p0, p.p1) > 1e-9:
                out.append(LineSeg(p.p0, p.p1))
        else:
            a0 = _ang(p.center, p.p0)
            sw = _arc_sweep(p)
            out.append(ArcSeg(p.center, p.radius, a0, sw if p.ccw else -sw))
        q = pieces[(j + 1) % n]
        if _dist(p.p1, q.p0) > 1e-9:
            out.append(LineSeg(p.p1, q.p0))
    return _merged(out)


def _merged(segs: List[Segment]) -> List[Segment]:
    """Consecutive collinear lines (a mitre piece and its line) as one line."""
    out: List[Segment] = []
    for s in segs:
        if out and isinstance(s, LineSeg) and isinstance(out[-1], LineSeg):
            a = out[-1]
            u = (a.end[0] - a.start[0], a.end[1] - a.start[1])
            v = (s.end[0] - s.start[0], s.end[1] - s.start[1])
            if abs(_cross(u, v)) <= 1e-9 * (a.length * s.length) and u[0] * v[0] + u[1] * v[1] > 0:
                out[-1] = LineSeg(a.start, s.end)
                continue
        out.append(s)
    return out


def offset_closed(segments: Sequence[Segment], d: float, corner: str = "round",
                  check: bool = True) -> List[Segment]:
    """The closed path ``segments`` offset ``d`` mm to its left (``d < 0``: to
    its right), starting near the same point and running the same way.

    ``corner``: ``"round"`` or ``"extended"``.  Raises :class:`OffsetError`
    when the offset vanishes, splits into several loops or (``check``) fails
    the comparison with shapely's buffer of the flattened contour."""
    if corner not in CORNERS:
        raise ValueError(f"corner must be one of {CORNERS}, not {corner!r}")
    segs = _basic(segments)
    if abs(d) < 1e-12 or not segs:
        return list(segments)
    ref = _reference(segs, d) if check else None   # raises for vanishing / splitting loops
    pieces = [p for p in (_offset_piece(s, d) for s in segs) if p is not None]
    if len(pieces) < 1:
        raise OffsetError("vanishes", f"the contour vanishes under an offset of {abs(d):g} mm")
    out = _emit(_trim(_with_joins(pieces, d, corner)))
    if ref is not None:
        _verify(segs, out, d, ref, corner)
    return out


def _side_region(segs: Sequence[Segment], d: float):
    """(shapely polygon of the drawn loop, True when the offset grows it)."""
    from shapely.geometry import Polygon

    from ..core.geometry import signed_area
    pts = path_points(segs, 0.002)
    ccw = signed_area(pts) > 0
    poly = Polygon(pts)
    if not poly.is_valid:
        poly = poly.buffer(0)
    # a left offset of a counter-clockwise loop goes inwards
    return poly, (d > 0) != ccw


def _reference(segs: Sequence[Segment], d: float):
    poly, grows = _side_region(segs, d)
    ref = poly.buffer(abs(d) if grows else -abs(d), quad_segs=32)
    if ref.is_empty:
        c = poly.representative_point()
        raise OffsetError("vanishes", f"the contour vanishes under an offset of {abs(d):g} mm "
                          f"(it is narrower than {2 * abs(d):g} mm)", (c.x, c.y))
    if ref.geom_type != "Polygon" or (grows and len(ref.interiors)):
        parts = getattr(ref, "geoms", [ref])
        c = min(parts, key=lambda g: g.area).representative_point()
        raise OffsetError("splits", f"a neck of the contour is narrower than {2 * abs(d):g} mm: "
                          f"the offset falls apart into {len(parts)} pieces", (c.x, c.y))
    return ref


#: Loops smaller than this (mm^2) where a drawing's micro-gaps make the offset
#: pieces overlap by a micron are not crossings.
MICRO_LOOP_AREA = 1e-3


def _micro_loops_only(pts: Sequence[Point]) -> bool:
    """Whether a self-touching loop is one region once loops of negligible
    area are removed (drawings join their pieces only to within microns)."""
    from shapely.geometry import Polygon

    from ..core.geometry import signed_area
    fixed = Polygon(pts).buffer(0)
    return fixed.geom_type == "Polygon" and \
        abs(fixed.area - abs(signed_area(pts))) < MICRO_LOOP_AREA


def _verify(segs: Sequence[Segment], out: Sequence[Segment], d: float, ref, corner: str) -> None:
    """Our path must be a simple loop at distance >= |d| from the drawn contour
    and (round corners) enclose the area of shapely's round buffer ``ref``
    within :data:`CHECK_TOL` times its perimeter."""
    import numpy as np
    import shapely
    from shapely.geometry import LinearRing, LineString

    pts = []
    for x, y in path_points(out, 0.002):
        # joins meet to ~1e-13 mm; a backtrack that small is no crossing
        p = (round(x, 7), round(y, 7))
        if not pts or p != pts[-1]:
            pts.append(p)
    if len(pts) < 4:
        raise OffsetError("vanishes", f"the contour vanishes under an offset of {abs(d):g} mm")
    ring = LinearRing(pts)
    if not ring.is_simple and not _micro_loops_only(pts):
        raise OffsetError("invalid", f"the offset path crosses itself: a feature is narrower "
                          f"than {2 * abs(d):g} mm", pts[0])
    drawn = LineString(path_points(segs, 0.002))
    sample = shapely.points(np.asarray(pts))
    near = shapely.distance(sample, drawn)
    k = int(np.argmin(near))
    if near[k] < abs(d) - CHECK_TOL:
        raise OffsetError("invalid", f"the offset path comes {near[k]:.3f} mm from the drawn "
                          f"contour (less than {abs(d):g} mm): a feature is narrower than the kerf",
                          pts[k])
    if corner == "round":
        from shapely.geometry import Polygon
        diff = abs(Polygon(pts).area - ref.area)
        if diff > CHECK_TOL * ref.exterior.length + 1e-6:
            raise OffsetError("invalid", f"the offset path encloses {diff:.3f} mm^2 more or less "
                              "than the buffered contour: a feature is narrower than the kerf",
                              pts[0])
