"""Generated drawings with known answers for the recognition tests and benchmark.

Every function returns plain model edges (mm, degrees) so a test can build a
:class:`Drawing` without the DXF importer.  Shapes are the canonical cases of
the recognition issue: common-edge grids drawn both ways, the pinwheel, gaps
around the tolerances, islands in holes, lead-ins, mirrored geometry, curves.
"""

from __future__ import annotations

import math
from typing import Dict, List, Optional, Sequence, Tuple

from LeatherCutWorkbench.core.model import (ArcEdge, Drawing, EdgeSource, EllipseEdge,
                                            LineEdge, Mark, SplineEdge)

Pt = Tuple[float, float]


def src(layer: str = "0", role: str = "cut", handle: str = "", block: str = "") -> EdgeSource:
    return EdgeSource(layer=layer, handle=handle, dxftype="LINE", block=block, role=role)


def drawing(edges: Sequence, marks: Sequence[Mark] = (), pieces: Optional[Dict] = None,
            texts: Sequence = ()) -> Drawing:
    return Drawing("generated.dxf", edges=list(edges), marks=list(marks),
                   pieces=dict(pieces or {}), texts=list(texts))


def polyline(pts: Sequence[Pt], closed: bool = True, **kw) -> List[LineEdge]:
    """Line edges through ``pts`` (closing back to the first when ``closed``)."""
    n = len(pts)
    m = n if closed else n - 1
    return [LineEdge(tuple(pts[i]), tuple(pts[(i + 1) % n]), src(**kw)) for i in range(m)]


def rect(x: float, y: float, w: float, h: float, **kw) -> List[LineEdge]:
    """Axis-aligned rectangle, counter-clockwise, four separate lines."""
    return polyline([(x, y), (x + w, y), (x + w, y + h), (x, y + h)], **kw)


def circle(cx: float, cy: float, r: float, **kw) -> ArcEdge:
    return ArcEdge((cx, cy), r, 0.0, 360.0, src(**kw))


def rounded_rect(x: float, y: float, w: float, h: float, r: float, **kw) -> list:
    """Rectangle with quarter-arc corners of radius ``r`` (lines + arcs)."""
    s = src(**kw)
    return [LineEdge((x + r, y), (x + w - r, y), s),
            ArcEdge((x + w - r, y + r), r, 270.0, 90.0, s),
            LineEdge((x + w, y + r), (x + w, y + h - r), s),
            ArcEdge((x + w - r, y + h - r), r, 0.0, 90.0, s),
            LineEdge((x + w - r, y + h), (x + r, y + h), s),
            ArcEdge((x + r, y + h - r), r, 90.0, 90.0, s),
            LineEdge((x, y + h - r), (x, y + r), s),
            ArcEdge((x + r, y + r), r, 180.0, 90.0, s)]


def grid_separate(nx: int, ny: int, size: float = 10.0, x0: float = 0.0, y0: float = 0.0) -> list:
    """nx x ny cells, each drawn as its own closed outline (shared edges twice)."""
    out: list = []
    for j in range(ny):
        for i in range(nx):
            out += rect(x0 + i * size, y0 + j * size, size, size)
    return out


def grid_lines(nx: int, ny: int, size: float = 10.0, x0: float = 0.0, y0: float = 0.0) -> list:
    """The same grid drawn as single long lines: a border of four lines and the
    inner lines crossing each other, ending on the border (T-junctions)."""
    w, h = nx * size, ny * size
    out = rect(x0, y0, w, h)
    for i in range(1, nx):
        out.append(LineEdge((x0 + i * size, y0), (x0 + i * size, y0 + h), src()))
    for j in range(1, ny):
        out.append(LineEdge((x0, y0 + j * size), (x0 + w, y0 + j * size), src()))
    return out


def grid_segments(nx: int, ny: int, size: float = 10.0) -> list:
    """The grid drawn with every cell side once (no duplicates, no T-junctions)."""
    out = []
    for j in range(ny + 1):
        for i in range(nx):
            out.append(LineEdge((i * size, j * size), ((i + 1) * size, j * size), src()))
    for i in range(nx + 1):
        for j in range(ny):
            out.append(LineEdge((i * size, j * size), (i * size, (j + 1) * size), src()))
    return out


def pinwheel_separate(x0: float = 0.0, y0: float = 0.0) -> list:
    """Four 20x10 parts drawn as closed rectangles around an empty 10x10 square
    (the square [10,20]x[10,20] is the scrap the arrangement also finds)."""
    return (rect(x0, y0, 20, 10) + rect(x0 + 20, y0, 10, 20)
            + rect(x0 + 10, y0 + 20, 20, 10) + rect(x0, y0 + 10, 10, 20))


def pinwheel_lines(x0: float = 0.0, y0: float = 0.0) -> list:
    """The same pinwheel drawn as single lines: a 30x30 border and four inner lines."""
    s = src()
    return rect(x0, y0, 30, 30) + [
        LineEdge((x0, y0 + 10), (x0 + 20, y0 + 10), s),
        LineEdge((x0 + 20, y0), (x0 + 20, y0 + 20), s),
        LineEdge((x0 + 30, y0 + 20), (x0 + 10, y0 + 20), s),
        LineEdge((x0 + 10, y0 + 30), (x0 + 10, y0 + 10), s)]


def square_with_gap(gap: float, x: float = 0.0, y: float = 0.0, size: float = 20.0) -> list:
    """Square whose last side stops ``gap`` mm short of the start point."""
    pts = [(x, y), (x + size, y), (x + size, y + size), (x, y + size)]
    out = polyline(pts, closed=False)
    out.append(LineEdge((x, y + size), (x, y + gap), src()))
    return out


def square_two_gaps(gap: float, x: float = 0.0, y: float = 0.0, size: float = 20.0) -> list:
    """Square drawn as two L-shaped chains with a ``gap`` at both joins."""
    a = polyline([(x, y), (x + size, y), (x + size, y + size - gap)], closed=False)
    b = polyline([(x + size, y + size), (x, y + size), (x, y + gap)], closed=False)
    return a + b


def square_overshoot(over: float, x: float = 0.0, y: float = 0.0, size: float = 20.0) -> list:
    """Square whose bottom line runs ``over`` mm past the lower right corner and
    whose right side starts on it (a T-junction short of the line end)."""
    s = src()
    return [LineEdge((x, y), (x + size + over, y), s),
            LineEdge((x + size, y), (x + size, y + size), s),
            LineEdge((x + size, y + size), (x, y + size), s),
            LineEdge((x, y + size), (x, y), s)]


def square_cross_overshoot(over: float, size: float = 20.0) -> list:
    """'#'-style square: every side overshoots both corners by ``over`` mm."""
    s = src()
    o = over
    return [LineEdge((-o, 0), (size + o, 0), s), LineEdge((size, -o), (size, size + o), s),
            LineEdge((size + o, size), (-o, size), s), LineEdge((0, size + o), (0, -o), s)]


def line_lead_in(px: float, py: float, length: float, angle_deg: float) -> LineEdge:
    """A straight lead-in ending at (px, py), arriving from ``angle_deg``."""
    a = math.radians(angle_deg)
    return LineEdge((px + length * math.cos(a), py + length * math.sin(a)), (px, py), src())


def part_with_hole(x: float, y: float, w: float = 40.0, h: float = 30.0,
                   hole_r: float = 5.0, lead_in: Optional[str] = "line") -> list:
    """Rectangle with a round hole in the middle and a lead-in at the lower left
    corner region: ``"line"`` (perpendicular, 3 mm) or ``"arc"`` (tangent quarter
    arc of radius 3 mm) touching the bottom edge 5 mm from the corner."""
    out = rect(x, y, w, h) + [circle(x + w / 2, y + h / 2, hole_r)]
    if lead_in == "line":
        out.append(line_lead_in(x + 5, y, 3.0, -90.0))
    elif lead_in == "arc":
        # centre below the contour: quarter arc from (x+2, y-3) to (x+5, y) tangent to +X
        out.append(ArcEdge((x + 5, y - 3), 3.0, 180.0, -90.0, src()))
    return out


def mirrored(edges: Sequence) -> list:
    """Mirror about the Y axis (x -> -x), as a mirrored block insert does."""
    out = []
    for e in edges:
        if isinstance(e, LineEdge):
            out.append(LineEdge((-e.start[0], e.start[1]), (-e.end[0], e.end[1]), e.src))
        elif isinstance(e, ArcEdge):
            out.append(ArcEdge((-e.center[0], e.center[1]), e.radius, 180.0 - e.start_angle,
                               -e.sweep, e.src))
        else:
            raise TypeError(type(e))
    return out


def ellipse(cx: float, cy: float, a: float, b: float, rot_deg: float = 0.0) -> EllipseEdge:
    r = math.radians(rot_deg)
    return EllipseEdge((cx, cy), (a * math.cos(r), a * math.sin(r)), b / a, 0.0, 2 * math.pi,
                       src())


def open_spline_with_line(x: float = 0.0, y: float = 0.0) -> list:
    """A clamped cubic B-spline arch from (x, y) to (x+40, y) closed by a line."""
    poles = [(x, y), (x + 5, y + 20), (x + 20, y + 30), (x + 35, y + 20), (x + 40, y)]
    knots = [0, 0, 0, 0, 0.5, 1, 1, 1, 1]
    return [SplineEdge(poles, knots, [], 3, src=src()),
            LineEdge((x + 40, y), (x, y), src())]


def shifted(edges: Sequence, dx: float, dy: float) -> list:
    out = []
    for e in edges:
        if isinstance(e, LineEdge):
            out.append(LineEdge((e.start[0] + dx, e.start[1] + dy),
                                (e.end[0] + dx, e.end[1] + dy), e.src))
        elif isinstance(e, ArcEdge):
            out.append(ArcEdge((e.center[0] + dx, e.center[1] + dy), e.radius, e.start_angle,
                               e.sweep, e.src))
        else:
            raise TypeError(type(e))
    return out


def many_parts(n: int, lead_in: str = "line") -> list:
    """``n`` separate 40x30 rectangles with a round hole and a lead-in each on a
    square-ish grid with 10 mm spacing (about 6 edges per part)."""
    cols = max(1, int(math.ceil(math.sqrt(n))))
    out: list = []
    for k in range(n):
        i, j = k % cols, k // cols
        out += part_with_hole(i * 50.0, j * 40.0, lead_in=lead_in)
    return out
