"""Hand-built cut plans and geometry checks shared by the post/link tests."""

from __future__ import annotations

import math
from typing import List, Tuple

from LeatherCutWorkbench.core.geometry import ArcSeg, CurveSeg, LineSeg, Point
from LeatherCutWorkbench.core.model import CutItem, CutPlan


def polyline(pts: List[Point]) -> List[LineSeg]:
    return [LineSeg(a, b) for a, b in zip(pts, pts[1:])]


def sample_plan(dx: float = 0.0, dy: float = 0.0) -> CutPlan:
    """A small leather job: a round hole (full circle), a slot hole with arcs,
    an outer contour with a lead-in, a rounded corner and a spline-like curve,
    and an open chain (a crease line).  About 300 x 200 mm, at (dx, dy)."""
    def t(p: Point) -> Point:
        return (p[0] + dx, p[1] + dy)

    hole = CutItem("C2", "P1", "hole", t((150, 100)),
                   [ArcSeg(t((130, 100)), 20.0, 0.0, -360.0)])
    # slot: two half circles and two lines, clockwise (a hole)
    slot = CutItem("C3", "P1", "hole", t((220, 80)), [
        LineSeg(t((220, 80)), t((200, 80))),
        ArcSeg(t((200, 90)), 10.0, -90.0, -180.0),
        LineSeg(t((200, 100)), t((220, 100))),
        ArcSeg(t((220, 90)), 10.0, 90.0, -180.0),
    ])
    curve = CurveSeg(tuple(t((300 - 40 * (1 - math.cos(math.radians(a))),
                              150 + 40 * math.sin(math.radians(a)))) for a in range(0, 91, 5)))
    outer_segs = [
        LineSeg(t((90, 40)), t((100, 50))),                 # lead-in at 45 degrees
        LineSeg(t((100, 50)), t((280, 50))),
        ArcSeg(t((280, 70)), 20.0, -90.0, 90.0),            # rounded corner (tangent)
        LineSeg(t((300, 70)), t((300, 150))),
        curve,                                               # ends at (260, 190)
        LineSeg(curve.end, t((100, 190))),
        LineSeg(t((100, 190)), t((100, 50))),
    ]
    outer = CutItem("C1", "P1", "outer", t((100, 50)), outer_segs, lead_in_count=1)
    crease = CutItem("O1", "", "open", t((120, 230)),
                     polyline([t((120, 230)), t((200, 240)), t((280, 230))]))
    return CutPlan([hole, slot, outer, crease], home=(0.0, 0.0))


def dist_to_segment(p: Point, seg) -> float:
    """Distance (mm) from ``p`` to a LineSeg / ArcSeg / CurveSeg."""
    if isinstance(seg, LineSeg):
        (ax, ay), (bx, by) = seg.start, seg.end
        vx, vy = bx - ax, by - ay
        n2 = vx * vx + vy * vy
        t = 0.0 if n2 == 0 else max(0.0, min(1.0, ((p[0] - ax) * vx + (p[1] - ay) * vy) / n2))
        return math.hypot(p[0] - ax - t * vx, p[1] - ay - t * vy)
    if isinstance(seg, ArcSeg):
        cx, cy = seg.center
        ang = math.degrees(math.atan2(p[1] - cy, p[0] - cx))
        rel = (ang - seg.start_angle) % 360.0 if seg.sweep > 0 else (seg.start_angle - ang) % 360.0
        if rel <= abs(seg.sweep) + 1e-6 or abs(seg.sweep) >= 360.0 - 1e-9:
            return abs(math.hypot(p[0] - cx, p[1] - cy) - seg.radius)
        return min(math.dist(p, seg.start), math.dist(p, seg.end))
    return min(dist_to_segment(p, LineSeg(a, b)) for a, b in zip(seg.pts, seg.pts[1:]))


def arc_mid(center: Tuple[float, float], start: Point, end: Point, ccw: bool) -> Point:
    cx, cy = center
    r = math.hypot(start[0] - cx, start[1] - cy)
    a0 = math.atan2(start[1] - cy, start[0] - cx)
    a1 = math.atan2(end[1] - cy, end[0] - cx)
    sweep = (a1 - a0) % (2 * math.pi) if ccw else -((a0 - a1) % (2 * math.pi))
    if abs(sweep) < 1e-12:
        sweep = 2 * math.pi if ccw else -2 * math.pi
    am = a0 + sweep / 2
    return (cx + r * math.cos(am), cy + r * math.sin(am))
