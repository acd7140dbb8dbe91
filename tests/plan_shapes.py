"""Real geometry for the path-planning tests and benchmark (no recognition
needed): parts built directly from core.geometry segments.

All lengths mm.  Outer contours counter-clockwise, holes clockwise.
"""

from __future__ import annotations

import math
import random
from typing import List, Optional, Sequence, Tuple

from LeatherCutWorkbench.core.geometry import ArcSeg, LineSeg, Point
from LeatherCutWorkbench.core.model import Contour, LeadIn, OpenChain, Part


def polygon_segments(pts: Sequence[Point]) -> List[LineSeg]:
    """Closed polygon through ``pts`` (first point not repeated)."""
    return [LineSeg(tuple(pts[i]), tuple(pts[(i + 1) % len(pts)])) for i in range(len(pts))]


def rect_pts(x0: float, y0: float, x1: float, y1: float, ccw: bool = True) -> List[Point]:
    pts = [(x0, y0), (x1, y0), (x1, y1), (x0, y1)]
    return pts if ccw else pts[::-1]


def blob_pts(cx: float, cy: float, r_min: float, r_max: float, n: int,
             rng: random.Random, ccw: bool = True) -> List[Point]:
    """Irregular star-shaped polygon with ``n`` vertices between r_min and r_max."""
    pts = []
    for i in range(n):
        a = 2 * math.pi * (i + rng.uniform(-0.3, 0.3)) / n
        r = rng.uniform(r_min, r_max)
        pts.append((cx + r * math.cos(a), cy + r * math.sin(a)))
    return pts if ccw else pts[::-1]


def circle_hole(id_: str, cx: float, cy: float, r: float) -> Contour:
    """A clockwise full circle (one ArcSeg)."""
    return Contour(id_, [ArcSeg((cx, cy), r, 0.0, -360.0)])


def part(id_: str, outer_pts: Sequence[Point], holes: Sequence[Contour] = (),
         lead_ins: Sequence[LeadIn] = (), parent_id: Optional[str] = None,
         excluded: bool = False) -> Part:
    return Part(id=id_, outer=Contour(f"{id_}.outer", polygon_segments(outer_pts)),
                holes=list(holes), lead_ins=list(lead_ins), parent_id=parent_id,
                excluded=excluded)


def nested_job() -> Tuple[List[Part], List[OpenChain]]:
    """A frame with a big square hole holding a small part (which has its own
    round hole), a part with two holes and a lead-in, a part with a lead-in on
    a hole, an excluded part and a stray open chain."""
    frame_hole = Contour("F.h0", polygon_segments(rect_pts(50, 50, 250, 250, ccw=False)))
    frame = part("F", rect_pts(0, 0, 300, 300), [frame_hole])
    inner = part("I", rect_pts(100, 100, 200, 200), [circle_hole("I.h0", 150, 150, 20)],
                 parent_id="F")
    li = LeadIn("P.li0", "P.outer", [LineSeg((380, -20), (400, 0))])
    p = part("P", rect_pts(400, 0, 600, 150),
             [Contour("P.h0", polygon_segments(rect_pts(420, 20, 480, 80, ccw=False))),
              circle_hole("P.h1", 540, 75, 25)], [li])
    hole_li = LeadIn("Q.li0", "Q.h0", [LineSeg((475, 300), (450, 300))])
    q = part("Q", rect_pts(400, 200, 600, 400),
             [Contour("Q.h0", polygon_segments(rect_pts(450, 250, 550, 350, ccw=False)))],
             [hole_li])
    x = part("X", rect_pts(700, 0, 800, 100), excluded=True)
    chain = OpenChain("C1", [LineSeg((700, 300), (800, 300)), LineSeg((800, 300), (800, 380))])
    return [frame, inner, p, q, x], [chain]


def shared_edge_job() -> List[Part]:
    """Three rectangles in a row sharing two edges (common-line cutting)."""
    a = part("A", rect_pts(0, 0, 100, 60))
    b = part("B", rect_pts(100, 0, 200, 60))
    c = part("C", rect_pts(200, 0, 300, 60))
    # rect_pts order: (x0,y0)->(x1,y0)->(x1,y1)->(x0,y1): segment 1 is the right
    # edge, segment 3 the left edge
    a.outer.shared = [1]
    b.outer.shared = [1, 3]
    c.outer.shared = [3]
    return [a, b, c]


def leather_job(seed: int = 1, n_parts: int = 62, n_holes: int = 9,
                size: float = 1000.0) -> List[Part]:
    """Synthetic leather job like the fact sheet's: ``n_parts`` irregular parts
    (radius 35-60 mm, 8-14 vertices) on a jittered grid over a size x size mm
    hide (at least 3 mm apart), ``n_holes`` of them with a round hole, listed in
    a shuffled (designer's) drawing order."""
    rng = random.Random(seed)
    cols = math.ceil(math.sqrt(n_parts))
    cell = size / cols
    cells = [(i, j) for i in range(cols) for j in range(cols)]
    rng.shuffle(cells)
    parts = []
    for k, (i, j) in enumerate(cells[:n_parts]):
        r_max = min(60.0, cell / 2 - 1.5)
        r_min = min(35.0, r_max * 0.7)
        slack = cell / 2 - 1.5 - r_max
        cx = (i + 0.5) * cell + rng.uniform(-slack, slack)
        cy = (j + 0.5) * cell + rng.uniform(-slack, slack)
        pts = blob_pts(cx, cy, r_min, r_max, rng.randint(8, 14), rng)
        holes = [circle_hole(f"L{k}.h0", cx, cy, 0.35 * r_min)] if k < n_holes else []
        parts.append(part(f"L{k}", pts, holes))
    return parts
