"""Extents of imported geometry (mm) and the move to a local origin.

Header extents (``$EXTMIN``/``$EXTMAX``) are often stale, so extents are
computed from the imported edges: lines, arcs and ellipses exactly, splines by
their control polygon (which contains the curve).
Infinite entities (XLINE, RAY) are never imported, so they never count.

Huge coordinates (survey or sheet offsets of ~1e6 mm and more) are moved to a
local origin before tolerance work: :func:`local_offset` picks a round offset
near the lower-left corner and :func:`translate` applies it to a drawing's
edges, marks and texts.
"""

from __future__ import annotations

import dataclasses
import math
from itertools import chain
from operator import attrgetter
from typing import Any, Iterable, Optional, Tuple

import numpy as np

from ..model import ArcEdge, EllipseEdge, LineEdge, SplineEdge

BBox = Tuple[float, float, float, float]

#: Coordinates beyond this (mm) from the origin trigger a local origin.
HUGE_COORDINATE_MM = 1.0e5


def edge_bounds(e: Any) -> BBox:
    """(xmin, ymin, xmax, ymax) in mm containing edge ``e``."""
    t = type(e)
    if t is LineEdge:
        (x1, y1), (x2, y2) = e.start, e.end
        return (min(x1, x2), min(y1, y2), max(x1, x2), max(y1, y2))
    if t is ArcEdge:
        return _arc_bounds(e)
    if t is EllipseEdge:
        return _ellipse_bounds(e)
    if t is SplineEdge:
        xs = [p[0] for p in e.poles]
        ys = [p[1] for p in e.poles]
        return (min(xs), min(ys), max(xs), max(ys))
    raise TypeError(f"unknown edge type {t.__name__}")


def _arc_bounds(e: ArcEdge) -> BBox:
    cx, cy = e.center
    r = e.radius
    if abs(e.sweep) >= 360.0:
        return (cx - r, cy - r, cx + r, cy + r)
    a0 = e.start_angle if e.sweep >= 0 else e.start_angle + e.sweep
    span = abs(e.sweep)
    angles = [a0, a0 + span]
    k = math.ceil(a0 / 90.0)
    while k * 90.0 < a0 + span:
        angles.append(k * 90.0)
        k += 1
    xs = [cx + r * math.cos(math.radians(a)) for a in angles]
    ys = [cy + r * math.sin(math.radians(a)) for a in angles]
    return (min(xs), min(ys), max(xs), max(ys))


def _ellipse_bounds(e: EllipseEdge) -> BBox:
    """Exact: end points plus the axis-extreme parameters inside the span."""
    (cx, cy), (mx, my) = e.center, e.major_axis
    nx, ny = -my * e.ratio, mx * e.ratio
    s0, s1 = e.start_param, e.end_param
    params = [s0, s1]
    for base in (math.atan2(nx, mx), math.atan2(ny, my)):   # dx/ds = 0, dy/ds = 0
        for cand in (base, base + math.pi):
            k = math.ceil((s0 - cand) / (2 * math.pi))
            s = cand + k * 2 * math.pi
            if s <= s1:
                params.append(s)
    xs = [cx + mx * math.cos(s) + nx * math.sin(s) for s in params]
    ys = [cy + my * math.cos(s) + ny * math.sin(s) for s in params]
    return (min(xs), min(ys), max(xs), max(ys))


def bounds(edges: Iterable[Any], points: Iterable[Tuple[float, float]] = ()) -> Optional[BBox]:
    """Union of the edges' bounds and the points; None when both are empty.
    Lines and arcs (nearly all edges) are handled with numpy."""
    lines, arcs, ellipses, boxes = [], [], [], []
    for e in edges:
        t = type(e)
        if t is LineEdge:
            lines.append(e)
        elif t is ArcEdge:
            arcs.append(e)
        elif t is EllipseEdge:
            ellipses.append(e)
        else:
            boxes.append(edge_bounds(e))
    boxes.extend((x, y, x, y) for x, y in points)
    ch = chain.from_iterable
    if lines:
        a = np.fromiter(ch(ch(map(attrgetter("start", "end"), lines))), float,
                        count=4 * len(lines)).reshape(-1, 4)
        boxes.append((a[:, 0::2].min(), a[:, 1::2].min(), a[:, 0::2].max(), a[:, 1::2].max()))
    if arcs:
        boxes.append(_arcs_bounds(np.fromiter(
            ch((*e.center, e.radius, e.start_angle, e.sweep) for e in arcs), float,
            count=5 * len(arcs)).reshape(-1, 5)))
    if ellipses:
        boxes.append(_ellipses_bounds(np.fromiter(
            ch((*e.center, *e.major_axis, e.ratio, e.start_param, e.end_param) for e in ellipses),
            float, count=7 * len(ellipses)).reshape(-1, 7)))
    if not boxes:
        return None
    b = np.array(boxes, dtype=float)
    return (float(b[:, 0].min()), float(b[:, 1].min()), float(b[:, 2].max()), float(b[:, 3].max()))


def _arcs_bounds(a: np.ndarray) -> BBox:
    """Exact box of arcs given as rows (cx, cy, r, start angle, signed sweep):
    end points plus every axis direction (0, 90, 180, 270 deg) inside the sweep."""
    cx, cy, r, a0, sw = a.T
    start = np.where(sw >= 0, a0, a0 + sw)
    span = np.abs(sw)
    xs = [cx + r * np.cos(np.radians(start)), cx + r * np.cos(np.radians(start + span))]
    ys = [cy + r * np.sin(np.radians(start)), cy + r * np.sin(np.radians(start + span))]
    for q, dx, dy in ((0.0, 1, 0), (90.0, 0, 1), (180.0, -1, 0), (270.0, 0, -1)):
        inside = (span >= 360.0) | (np.mod(q - start, 360.0) <= span)
        xs.append(np.where(inside, cx + dx * r, xs[0]))
        ys.append(np.where(inside, cy + dy * r, ys[0]))
    x, y = np.stack(xs), np.stack(ys)
    return (x.min(), y.min(), x.max(), y.max())


def _ellipses_bounds(a: np.ndarray) -> BBox:
    """Exact box of elliptical arcs given as rows (cx, cy, mx, my, ratio, s0, s1):
    end points plus the parameters where dx/ds or dy/ds vanish inside [s0, s1]."""
    cx, cy, mx, my, ratio, s0, s1 = a.T
    nx, ny = -my * ratio, mx * ratio
    params = [s0, s1]
    for base in (np.arctan2(nx, mx), np.arctan2(ny, my)):
        for cand in (base, base + math.pi):
            s = cand + np.ceil((s0 - cand) / (2 * math.pi)) * 2 * math.pi
            params.append(np.where(s <= s1, s, s0))
    p = np.stack(params)
    x = cx + mx * np.cos(p) + nx * np.sin(p)
    y = cy + my * np.cos(p) + ny * np.sin(p)
    return (x.min(), y.min(), x.max(), y.max())


def local_offset(box: Optional[BBox], limit: float = HUGE_COORDINATE_MM) -> Tuple[float, float]:
    """Offset (mm) to subtract so huge coordinates become local; (0, 0) when
    the drawing lies within ``limit`` of the origin.  Rounded down to whole
    metres so local coordinates stay readable."""
    if box is None or max(abs(v) for v in box) <= limit:
        return (0.0, 0.0)
    return (math.floor(box[0] / 1000.0) * 1000.0, math.floor(box[1] / 1000.0) * 1000.0)


def _shift(p, dx: float, dy: float):
    return (p[0] - dx, p[1] - dy)


def translate(items: Iterable[Any], dx: float, dy: float) -> list:
    """Copies of edges / marks / texts moved by (-dx, -dy) mm."""
    out = []
    for it in items:
        if isinstance(it, LineEdge):
            out.append(dataclasses.replace(it, start=_shift(it.start, dx, dy), end=_shift(it.end, dx, dy)))
        elif isinstance(it, SplineEdge):
            out.append(dataclasses.replace(it, poles=[_shift(p, dx, dy) for p in it.poles]))
        elif hasattr(it, "center"):
            out.append(dataclasses.replace(it, center=_shift(it.center, dx, dy)))
        else:  # Mark, TextNote
            out.append(dataclasses.replace(it, position=_shift(it.position, dx, dy)))
    return out
