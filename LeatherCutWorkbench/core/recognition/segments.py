"""Segment geometry for the edge graph: a grid index over segment boxes, point
on segment (split at a T-junction), line crossings, nearest points.

Pure Python, exact for lines and arcs, on the flattened polyline for curves.
Lengths mm, angles degrees.
"""

from __future__ import annotations

import math
from collections import defaultdict
from typing import TYPE_CHECKING, Dict, List, Optional, Tuple

from ..geometry import ArcSeg, CurveSeg, LineSeg, Point, Segment

if TYPE_CHECKING:  # graph imports this module: only the type is needed here
    from .graph import Piece


#: A segment whose box covers more grid cells than this is kept in a short
#: list tested by every query instead (one long line beside many short ones
#: would otherwise fill millions of cells).
MAX_CELLS_PER_SEGMENT = 1024


class SegmentIndex:
    """Uniform grid over segment bounding boxes (cell about the median size);
    boxes are kept as tuples so a point query filters without geometry.
    Segments spanning more than :data:`MAX_CELLS_PER_SEGMENT` cells are
    listed in ``big`` and checked by every query."""

    def __init__(self, pieces: List[Piece], tol: float, chord_tol: float = 0.0):
        self.tol = tol
        self.chord_tol = chord_tol          # flattened curves deviate this much
        self.boxes: List[Tuple[float, float, float, float]] = [seg_bbox(p.seg) for p in pieces]
        step = max(1, len(self.boxes) // 1000)
        sizes = sorted(max(b[2] - b[0], b[3] - b[1]) for b in self.boxes[::step])
        med = sizes[len(sizes) // 2] if sizes else 1.0
        self.cell = max(med, 10 * tol, 1e-6)
        self.cells: Dict[Tuple[int, int], List[int]] = defaultdict(list)
        self.big: List[int] = []
        for i in range(len(self.boxes)):
            self._insert(i)
        self._indexed = len(pieces)

    def _insert(self, i: int) -> None:
        x0, y0, x1, y1 = self.boxes[i]
        t, c = self.tol, self.cell
        ix0, ix1 = math.floor((x0 - t) / c), math.floor((x1 + t) / c)
        iy0, iy1 = math.floor((y0 - t) / c), math.floor((y1 + t) / c)
        cells = self.cells
        if ix0 == ix1 and iy0 == iy1:
            cells[(ix0, iy0)].append(i)
            return
        if (ix1 - ix0 + 1) * (iy1 - iy0 + 1) > MAX_CELLS_PER_SEGMENT:
            self.big.append(i)
            return
        for ix in range(ix0, ix1 + 1):
            for iy in range(iy0, iy1 + 1):
                cells[(ix, iy)].append(i)

    def update(self, pieces: List[Piece], i: int) -> None:
        """Piece ``i`` was replaced by its first part and the rest appended.
        Stale entries of ``i`` stay (callers re-test geometry anyway)."""
        self.boxes[i] = seg_bbox(pieces[i].seg)
        self._insert(i)
        for k in range(self._indexed, len(pieces)):
            self.boxes.append(seg_bbox(pieces[k].seg))
            self._insert(k)
        self._indexed = len(pieces)

    def near(self, p: Point, radius: float = 0.0) -> List[int]:
        """Pieces whose box (grown by the tolerance + ``radius``) holds ``p``."""
        c = self.cell
        x, y = p
        r = self.tol + radius
        out = []
        boxes = self.boxes
        if radius <= 0:
            keys = [(math.floor(x / c), math.floor(y / c))]
        else:
            ix0, ix1 = math.floor((x - r) / c), math.floor((x + r) / c)
            iy0, iy1 = math.floor((y - r) / c), math.floor((y + r) / c)
            if (ix1 - ix0 + 1) * (iy1 - iy0 + 1) > MAX_CELLS_PER_SEGMENT:
                # a query wider than the grid is worth: test every box
                return [j for j, b in enumerate(boxes)
                        if b[0] - r <= x <= b[2] + r and b[1] - r <= y <= b[3] + r]
            keys = [(ix, iy) for ix in range(ix0, ix1 + 1) for iy in range(iy0, iy1 + 1)]
        for key in keys:
            for j in self.cells.get(key, ()):
                b = boxes[j]
                if b[0] - r <= x <= b[2] + r and b[1] - r <= y <= b[3] + r:
                    out.append(j)
        for j in self.big:
            b = boxes[j]
            if b[0] - r <= x <= b[2] + r and b[1] - r <= y <= b[3] + r:
                out.append(j)
        return out


def seg_bbox(seg: Segment) -> Tuple[float, float, float, float]:
    if isinstance(seg, LineSeg):
        (ax, ay), (bx, by) = seg.start, seg.end
        return (min(ax, bx), min(ay, by), max(ax, bx), max(ay, by))
    if isinstance(seg, ArcSeg):
        cx, cy = seg.center
        r = seg.radius
        return (cx - r, cy - r, cx + r, cy + r)
    xs = [p[0] for p in seg.pts]
    ys = [p[1] for p in seg.pts]
    return (min(xs), min(ys), max(xs), max(ys))


def with_end(seg: Segment, p: Point) -> Segment:
    if isinstance(seg, LineSeg):
        return LineSeg(seg.start, p)
    if isinstance(seg, CurveSeg):
        return CurveSeg(seg.pts[:-1] + (p,), seg.kind)
    return seg


def with_start(seg: Segment, p: Point) -> Segment:
    if isinstance(seg, LineSeg):
        return LineSeg(p, seg.end)
    if isinstance(seg, CurveSeg):
        return CurveSeg((p,) + seg.pts[1:], seg.kind)
    return seg


def split_at_point(seg: Segment, p: Point, tol: float) -> Optional[List[Segment]]:
    """Two pieces of ``seg`` split where ``p`` lies on its interior (within
    ``tol`` mm, and farther than ``tol`` from both ends), else None."""
    x, y = p
    if isinstance(seg, LineSeg):
        (ax, ay), (bx, by) = seg.start, seg.end
        dx, dy = bx - ax, by - ay
        n2 = dx * dx + dy * dy
        if n2 <= 0:
            return None
        t = ((x - ax) * dx + (y - ay) * dy) / n2
        n = math.sqrt(n2)
        if t * n <= tol or (1 - t) * n <= tol:
            return None
        if abs((x - ax) * dy - (y - ay) * dx) / n > tol:
            return None
        q = (ax + t * dx, ay + t * dy)
        return [LineSeg(seg.start, q), LineSeg(q, seg.end)]
    if isinstance(seg, ArcSeg):
        cx, cy = seg.center
        if abs(math.hypot(x - cx, y - cy) - seg.radius) > tol:
            return None
        ang = math.degrees(math.atan2(y - cy, x - cx))
        rel = (ang - seg.start_angle) % 360.0 if seg.sweep > 0 else (seg.start_angle - ang) % 360.0
        s = math.radians(rel) * seg.radius
        if s <= tol or seg.length - s <= tol:
            return None
        a, b = seg.split_at(s)
        return [a, b]
    best = None
    pts = seg.pts
    acc = 0.0
    for i in range(len(pts) - 1):
        (ax, ay), (bx, by) = pts[i], pts[i + 1]
        dx, dy = bx - ax, by - ay
        n2 = dx * dx + dy * dy
        n = math.sqrt(n2)
        t = 0.0 if n2 == 0 else min(1.0, max(0.0, ((x - ax) * dx + (y - ay) * dy) / n2))
        d = math.hypot(ax + t * dx - x, ay + t * dy - y)
        if d <= tol and (best is None or d < best[0]):
            best = (d, acc + t * n)
        acc += n
    if best is None or best[1] <= tol or acc - best[1] <= tol:
        return None
    a, b = seg.split_at(best[1])
    return [a, b]


def line_cross(a: LineSeg, b: LineSeg, tol: float) -> Optional[Point]:
    """Proper crossing point of two lines (interior of both, not at an end)."""
    (x1, y1), (x2, y2) = a.start, a.end
    (x3, y3), (x4, y4) = b.start, b.end
    d = (x2 - x1) * (y4 - y3) - (y2 - y1) * (x4 - x3)
    la = math.hypot(x2 - x1, y2 - y1)
    lb = math.hypot(x4 - x3, y4 - y3)
    if la == 0 or lb == 0 or abs(d) <= 1e-12 * la * lb:
        return None
    t = ((x3 - x1) * (y4 - y3) - (y3 - y1) * (x4 - x3)) / d
    u = ((x3 - x1) * (y2 - y1) - (y3 - y1) * (x2 - x1)) / d
    if t * la <= tol or (1 - t) * la <= tol or u * lb <= tol or (1 - u) * lb <= tol:
        return None
    return (x1 + t * (x2 - x1), y1 + t * (y2 - y1))


def nearest_on(seg: Segment, p: Point) -> Tuple[float, Point]:
    """(distance, nearest point) from ``p`` to a segment (exact for lines and
    arcs, on the polyline for curves)."""
    x, y = p
    if isinstance(seg, ArcSeg):
        cx, cy = seg.center
        ang = math.degrees(math.atan2(y - cy, x - cx))
        rel = (ang - seg.start_angle) % 360.0 if seg.sweep > 0 else (seg.start_angle - ang) % 360.0
        if rel <= abs(seg.sweep):
            q = seg.point_at(math.radians(rel) * seg.radius)
        else:
            q = min((seg.start, seg.end), key=lambda e: math.hypot(e[0] - x, e[1] - y))
        return math.hypot(q[0] - x, q[1] - y), q
    pts = [seg.start, seg.end] if isinstance(seg, LineSeg) else list(seg.pts)
    best = None
    for (ax, ay), (bx, by) in zip(pts, pts[1:]):
        dx, dy = bx - ax, by - ay
        n2 = dx * dx + dy * dy
        t = 0.0 if n2 == 0 else min(1.0, max(0.0, ((x - ax) * dx + (y - ay) * dy) / n2))
        q = (ax + t * dx, ay + t * dy)
        d = math.hypot(q[0] - x, q[1] - y)
        if best is None or d < best[0]:
            best = (d, q)
    return best
