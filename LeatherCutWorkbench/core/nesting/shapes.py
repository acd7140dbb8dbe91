"""Part geometry as the nesting engine sees it.

A :class:`PieceType` is one part (true shape, mm): an outer ring (CCW) and
hole rings (CW) as float arrays, its quantity and what it may do (allowed
angles, mirroring, grade).  A :class:`Variant` is one orientation of a piece
type -- mirrored about the part's Y axis first, then rotated about the part's
origin -- in the engine's integer grid (pyclipper works on integers):

* ``outer``: the outline inflated by half the spacing, plus the chord error
  of flattened arcs and round joins, plus one grid unit (so rounding of
  clipped vertices can never create a real overlap),
* ``holes``: the holes shrunk by the same amount (room for part-in-part),
* ``core``: the true outline grown only by the chord error and one unit (for
  hide regions, whose margins are applied to the region instead),
* ``hull`` / ``core_hull``: the convex hulls of ``outer`` / ``core`` (the
  coarse geometry the engine falls back to when time runs short).

Orientations that give the same shape up to a translation (a rectangle turned
180 degrees, a disc turned any angle) are kept once.

The placement of a copy is a translation of its variant; the reference point
is the part origin, exactly like :class:`~LeatherCutWorkbench.core.model.Placement`.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from typing import List, Optional, Sequence

import numpy as np
import pyclipper

from ..errors import InputError
from ..geometry import signed_area
from ..model import Part

IntPath = List[List[int]]


@dataclass
class PieceType:
    """One part's true shape (mm) and nesting rules."""

    key: str
    outer: np.ndarray
    holes: List[np.ndarray]
    quantity: int = 1
    angles: List[float] = field(default_factory=lambda: [0.0])
    mirror: bool = False
    grade: int = 0
    tol: float = 0.0          # chord error of ``outer`` / ``holes`` (mm), covered by the growth

    @property
    def area(self) -> float:
        return abs(_area(self.outer)) - sum(abs(_area(h)) for h in self.holes)


@dataclass
class Variant:
    """One orientation of a piece type in grid units (see module doc)."""

    index: int
    type_index: int
    angle: float
    mirrored: bool
    outer: IntPath
    holes: List[IntPath]
    bbox: tuple  # (xmin, ymin, xmax, ymax) of ``outer``, grid units
    core: IntPath = field(default_factory=list)   # true outline grown by one grid unit
    hull: IntPath = field(default_factory=list)   # convex hull of ``outer`` (CCW)
    core_hull: IntPath = field(default_factory=list)   # convex hull of ``core`` (CCW)


def convex_hull(ring: IntPath) -> IntPath:
    """Convex hull of an integer ring, counter-clockwise, collinear points
    dropped (exact integers; Andrew's monotone chain -- a plain loop is
    several times faster than scipy on the few dozen vertices of a part)."""
    pts = sorted({(int(x), int(y)) for x, y in ring})
    if len(pts) < 3:
        return [list(p) for p in pts]

    def half(points):
        out: list = []
        for p in points:
            while len(out) >= 2 and ((out[-1][0] - out[-2][0]) * (p[1] - out[-2][1])
                                     - (out[-1][1] - out[-2][1]) * (p[0] - out[-2][0])) <= 0:
                out.pop()
            out.append(p)
        return out

    lower, upper = half(pts), half(pts[::-1])
    return [list(p) for p in lower[:-1] + upper[:-1]]


def _area(a: np.ndarray) -> float:
    x, y = a[:, 0], a[:, 1]
    return 0.5 * float(np.dot(x, np.roll(y, -1)) - np.dot(np.roll(x, -1), y))


def _ring(points: Sequence, ccw: bool) -> np.ndarray:
    a = np.asarray(points, dtype=float)
    if len(a) > 1 and np.allclose(a[0], a[-1]):
        a = a[:-1]
    if (_area(a) > 0) != ccw:
        a = a[::-1]
    return a


def allowed_angles(rotations: Optional[Sequence[float]], step: float) -> List[float]:
    """The angles tried for a part: its own list, or every ``step`` degrees."""
    if rotations is None:
        n = max(1, int(round(360.0 / step)))
        return [round(i * 360.0 / n, 9) for i in range(n)]
    out = sorted({round(float(a) % 360.0, 9) for a in rotations})
    return out or [0.0]


def nesting_tolerance(part: Part, chord_tol: float) -> float:
    """Chord tolerance (mm) for the engine's copy of a part with arcs: the finer
    of 0.2 % of its size and 0.5 mm, never below ``chord_tol`` (0 when the part
    has no arcs).  The engine grows the shape by this much, so the coarse
    polygon still covers the true one."""
    from ..geometry import ArcSeg
    if not any(isinstance(s, ArcSeg) for c in part.contours() for s in c.segments):
        return 0.0                    # straight segments and polylines are exact
    x0, y0, x1, y1 = part.outer.bbox
    return max(chord_tol, min(0.5, 0.002 * max(x1 - x0, y1 - y0)))


def piece_from_part(part: Part, chord_tol: float, step: float,
                    rotations: Optional[List[float]] = None,
                    mirror_override: Optional[bool] = None) -> PieceType:
    """Flatten a part's contours for the engine (see :func:`nesting_tolerance`);
    ``rotations`` are the allowed angles (None = any, every ``step`` degrees)."""
    tol = nesting_tolerance(part, chord_tol)
    outer = part.outer.points(tol or chord_tol)
    if len(outer) < 3 or abs(signed_area(outer)) <= 0:
        raise InputError(f"part {part.id}: outer contour has no area, cannot be nested")
    holes = [_ring(h.points(tol or chord_tol), ccw=False) for h in part.holes
             if len(h.points(tol or chord_tol)) >= 3]
    if part.quantity < 0:
        raise InputError(f"part {part.id}: quantity {part.quantity} is negative")
    return PieceType(key=part.id, outer=_ring(outer, ccw=True), holes=holes,
                     quantity=int(part.quantity), angles=allowed_angles(rotations, step),
                     mirror=part.mirror_allowed if mirror_override is None else mirror_override,
                     grade=int(part.grade), tol=tol)


def transform_ring(ring: np.ndarray, angle: float, mirrored: bool, dx: float = 0.0,
                   dy: float = 0.0) -> np.ndarray:
    """Mirror about Y, rotate ``angle`` degrees about the origin, translate (mm)."""
    a = ring.copy()
    if mirrored:
        a[:, 0] = -a[:, 0]
        a = a[::-1]          # mirroring flips the orientation: restore it
    t = math.radians(angle)
    c, s = math.cos(t), math.sin(t)
    out = np.empty_like(a)
    out[:, 0] = c * a[:, 0] - s * a[:, 1] + dx
    out[:, 1] = s * a[:, 0] + c * a[:, 1] + dy
    return out


def to_grid(ring: np.ndarray, scale: float) -> IntPath:
    """``ring`` (mm) in grid units, rounded half to even like ``round`` (numpy:
    ~10x faster on hide outlines and holes than a loop)."""
    return np.rint(np.asarray(ring, dtype=np.float64) * scale).astype(np.int64).tolist()


def offset_paths(paths: List[IntPath], delta: float, arc_tol: float) -> List[IntPath]:
    """Grow (delta > 0) or shrink a set of closed grid paths: round joins for a
    real spacing, mitred joins for the few-unit rounding guard (no tiny arcs)."""
    if delta == 0:
        return [list(p) for p in paths]
    joint = pyclipper.JT_ROUND if abs(delta) > 4 * max(arc_tol, 2.0) else pyclipper.JT_MITER
    off = pyclipper.PyclipperOffset(2.0, max(arc_tol, 0.25))
    off.AddPaths([pyclipper.CleanPolygon(p, 2.0) for p in paths], joint,
                 pyclipper.ET_CLOSEDPOLYGON)
    return [pyclipper.CleanPolygon(p, 2.0) for p in off.Execute(delta)]


def _same_shape(a: np.ndarray, b: np.ndarray, tol: float) -> bool:
    """Are two rings the same shape up to translation (within ``tol`` mm)?"""
    from shapely.geometry import Polygon
    da, db = a.max(axis=0) - a.min(axis=0), b.max(axis=0) - b.min(axis=0)
    if np.abs(da - db).max() > 4.0 * tol + 1e-9 * float(da.max()):
        return False                  # different bounding boxes: cheaply not the same
    pa = Polygon(a - a.min(axis=0))
    pb = Polygon(b - b.min(axis=0))
    if abs(pa.area - pb.area) > tol * pa.length + 1e-9 * pa.area:
        return False
    return pa.symmetric_difference(pb).area <= 2.0 * tol * pa.length + 1e-9 * pa.area


def distinct_orientations(t: PieceType) -> List[tuple]:
    """(angle, mirrored) pairs of ``t`` whose shapes differ: a rectangle turned
    180 degrees or a circle turned any angle is the same shape moved, so only
    the first such orientation is kept (the kept one covers the true shape;
    dropping the others only removes duplicate work)."""
    keep: List[tuple] = []
    shapes: List[np.ndarray] = []
    tol = t.tol if t.tol > 0 else 1e-9
    for m in ([False, True] if t.mirror else [False]):
        for ang in t.angles:
            ring = transform_ring(t.outer, ang, m)
            if t.holes or not any(_same_shape(ring, s, tol) for s in shapes):
                keep.append((ang, m))
                shapes.append(ring)
    return keep


def make_variants(types: Sequence[PieceType], scale: float, half_gap: float,
                  arc_tol: float) -> List[Variant]:
    """Every allowed orientation of every type, inflated by ``half_gap`` mm plus
    the type's chord tolerance (flattening) and the round-join sag plus one grid
    unit (see module doc); holes shrunk alike."""
    out: List[Variant] = []
    for ti, t in enumerate(types):
        # round joins of the spacing offset cut corners by about join_tol, but
        # pyclipper rounds the number of chord steps: a 90-degree corner of a small
        # offset may get a single chord that sags ~2.25 x join_tol (measured: 0.212
        # of a 0.25 mm half gap), so 2.5 x join_tol is allowed
        join_tol = max(arc_tol, t.tol, 0.01 * half_gap)
        sag = t.tol + (2.5 * join_tol if half_gap > 0 else 0.0)
        grow = (half_gap + sag) * scale + 1.0
        core_grow = t.tol * scale + 1.0
        for ang, m in distinct_orientations(t):
                outer = to_grid(transform_ring(t.outer, ang, m), scale)
                core = offset_paths([outer], core_grow, join_tol * scale)
                core = max(core, key=lambda p: abs(pyclipper.Area(p)))
                if pyclipper.Orientation(core) is False:
                    core = core[::-1]
                grown = offset_paths([outer], grow, join_tol * scale)
                grown = max(grown, key=lambda p: abs(pyclipper.Area(p)))
                if pyclipper.Orientation(grown) is False:
                    grown = grown[::-1]
                holes: List[IntPath] = []
                for h in t.holes:
                    hp = to_grid(transform_ring(h, ang, m), scale)
                    if not pyclipper.Orientation(hp):
                        hp = hp[::-1]
                    for sh in offset_paths([hp], -grow, join_tol * scale):
                        if abs(pyclipper.Area(sh)) > 0:
                            holes.append(sh if pyclipper.Orientation(sh) else sh[::-1])
                xs = [p[0] for p in grown]
                ys = [p[1] for p in grown]
                out.append(Variant(len(out), ti, ang, m, grown, holes,
                                   (min(xs), min(ys), max(xs), max(ys)), core,
                                   convex_hull(grown), convex_hull(core)))
    return out
