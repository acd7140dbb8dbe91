"""Half pattern pieces drawn against a fold (mirror) line -> the whole piece.

AAMA / ASTM layer 6 marks a fold line: the drawn piece is half of the piece to
cut.  When the outer contour runs along that line, the part is unfolded: the
segments on the line are dropped, the rest is reflected about the line and the
two halves are joined into one closed outline (still counter-clockwise); holes
and marks are reflected too.  Lengths mm, angles degrees.
"""

from __future__ import annotations

import math
from typing import Callable, List, Optional, Sequence, Tuple

from ..geometry import ArcSeg, CurveSeg, LineSeg, Point, Segment
from ..model import Contour, Mark, OpenChain, Part


class Reflection:
    """Reflection about the infinite line through ``a`` and ``b``."""

    def __init__(self, a: Point, b: Point):
        self.a = a
        dx, dy = b[0] - a[0], b[1] - a[1]
        n = math.hypot(dx, dy)
        self.ux, self.uy = dx / n, dy / n
        self.theta = math.degrees(math.atan2(dy, dx))

    def distance(self, p: Point) -> float:
        return abs((p[0] - self.a[0]) * self.uy - (p[1] - self.a[1]) * self.ux)

    def point(self, p: Point) -> Point:
        px, py = p[0] - self.a[0], p[1] - self.a[1]
        t = px * self.ux + py * self.uy
        fx, fy = t * self.ux, t * self.uy
        return (self.a[0] + 2 * fx - px, self.a[1] + 2 * fy - py)

    def segment(self, s: Segment) -> Segment:
        if isinstance(s, LineSeg):
            return LineSeg(self.point(s.start), self.point(s.end))
        if isinstance(s, ArcSeg):
            return ArcSeg(self.point(s.center), s.radius, 2 * self.theta - s.start_angle, -s.sweep)
        return CurveSeg(tuple(self.point(p) for p in s.pts), s.kind)

    def path(self, segs: Sequence[Segment]) -> List[Segment]:
        """Reflected and reversed: a reflected closed path keeps its orientation."""
        return [self.segment(s).reversed() for s in reversed(segs)]


def _on_line(seg: Segment, refl: Reflection, tol: float) -> bool:
    return (isinstance(seg, LineSeg) and refl.distance(seg.start) <= tol
            and refl.distance(seg.end) <= tol)


def unfold_part(part: Part, line: Tuple[Point, Point], tol: float,
                new_id: Callable[[], str]) -> Optional[str]:
    """Unfold ``part`` in place about ``line`` when its outer contour runs along
    it (reflected holes get ids from ``new_id``); returns None when done, else
    why it was left as drawn."""
    if math.hypot(line[1][0] - line[0][0], line[1][1] - line[0][1]) <= tol:
        return "the fold line has no length"
    refl = Reflection(*line)
    segs = list(part.outer.segments)
    on = [_on_line(s, refl, tol) for s in segs]
    if not any(on):
        return "the outline does not run along the fold line"
    if all(on):
        return "the whole outline lies on the fold line"
    # rotate so the first segment is the first one off the line after the fold run
    k = next(i for i in range(len(segs)) if on[i - 1] and not on[i])
    segs = segs[k:] + segs[:k]
    on = on[k:] + on[:k]
    last_off = max(i for i, v in enumerate(on) if not v)
    if any(on[: last_off + 1]):
        return "the outline touches the fold line more than once"
    half = segs[: last_off + 1]
    whole = half + refl.path(half)
    part.outer = Contour(part.outer.id, whole, part.outer.layer, [])
    part.holes = part.holes + [Contour(new_id(), refl.path(h.segments), h.layer, [])
                               for h in part.holes if not any(_on_line(s, refl, tol)
                                                              for s in h.segments)]
    part.marks = part.marks + [Mark(refl.point(m.position), m.kind, m.src) for m in part.marks
                               if refl.distance(m.position) > tol]
    part.lines = part.lines + [OpenChain(ln.id + "m", refl.path(ln.segments), ln.layer)
                               for ln in part.lines
                               if not all(_on_line(s, refl, tol) for s in ln.segments)]
    return None
