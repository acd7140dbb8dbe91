"""Real part geometry for the nesting tests (rectangles, L-shapes, circles as
ArcSeg, rings with holes) built from core.geometry segments."""

from typing import List, Optional, Sequence, Tuple

from LeatherCutWorkbench.core.geometry import ArcSeg, LineSeg
from LeatherCutWorkbench.core.model import Contour, Part


def poly_contour(cid: str, pts: Sequence[Tuple[float, float]]) -> Contour:
    return Contour(cid, [LineSeg(pts[i], pts[(i + 1) % len(pts)]) for i in range(len(pts))])


def rect(pid: str, w: float, h: float, q: int = 1, rotations: Optional[List[float]] = None,
         grade: int = 0, mirror: bool = False) -> Part:
    return Part(id=pid, outer=poly_contour(pid + "/o", [(0, 0), (w, 0), (w, h), (0, h)]),
                quantity=q, rotations=rotations, grade=grade, mirror_allowed=mirror)


def l_shape(pid: str, a: float, b: float, t: float, q: int = 1,
            rotations: Optional[List[float]] = None, mirror: bool = False) -> Part:
    pts = [(0, 0), (a, 0), (a, t), (t, t), (t, b), (0, b)]
    return Part(id=pid, outer=poly_contour(pid + "/o", pts), quantity=q, rotations=rotations,
                mirror_allowed=mirror)


def circle(cid: str, r: float, cx: float = 0.0, cy: float = 0.0, ccw: bool = True) -> Contour:
    return Contour(cid, [ArcSeg((cx, cy), r, 0.0, 360.0 if ccw else -360.0)])


def disc(pid: str, r: float, q: int = 1) -> Part:
    return Part(id=pid, outer=circle(pid + "/o", r, r, r), quantity=q, rotations=[0.0])


def ring(pid: str, r_out: float, r_in: float, q: int = 1) -> Part:
    return Part(id=pid, outer=circle(pid + "/o", r_out), holes=[circle(pid + "/h", r_in, ccw=False)],
                quantity=q, rotations=[0.0])


def frame(pid: str, w: float, h: float, t: float, q: int = 1) -> Part:
    """A rectangular frame: outer w x h, one rectangular hole with walls t."""
    hole = poly_contour(pid + "/h", [(t, t), (t, h - t), (w - t, h - t), (w - t, t)])
    return Part(id=pid, outer=poly_contour(pid + "/o", [(0, 0), (w, 0), (w, h), (0, h)]),
                holes=[hole], quantity=q, rotations=[0.0])


def write_hide_dxf(path: str, size: Tuple[float, float], hide_layer: str, zone_layer: str,
                   zone: Tuple[float, float, float, float]) -> None:
    """A rectangular hide (``size`` = w x h mm, from the origin) on ``hide_layer``
    with one rectangular zone (x0, y0, x1, y1) on ``zone_layer``, as a DXF."""
    import ezdxf
    doc = ezdxf.new(units=4)
    msp = doc.modelspace()
    for name in (hide_layer, zone_layer):
        doc.layers.add(name)
    w, h = size
    x0, y0, x1, y1 = zone
    msp.add_lwpolyline([(0, 0), (w, 0), (w, h), (0, h)], close=True,
                       dxfattribs={"layer": hide_layer})
    msp.add_lwpolyline([(x0, y0), (x1, y0), (x1, y1), (x0, y1)], close=True,
                       dxfattribs={"layer": zone_layer})
    doc.saveas(path)


def assert_same_fit_region(fast, slow, ring, outline) -> None:
    """Two inner-fit regions (grid paths) of the grid ring ``ring`` in the
    shapely ``outline``: the same area (to rounding), and copies of the ring
    at every eighth vertex of ``fast`` lie inside the outline."""
    from shapely.affinity import translate
    from shapely.geometry import Polygon
    a_fast = sum(Polygon(r).area for r in fast)
    a_slow = sum(Polygon(r).area for r in slow)
    assert abs(a_fast - a_slow) <= 1e-3 * a_slow + 1e3
    for r in fast:
        for x, y in r[::max(1, len(r) // 8)]:
            placed = translate(Polygon(ring), x, y)
            assert placed.difference(outline).area < 1e-4 * placed.area
