"""Containers: sheets, strips and leather hides (outline, defects, quality zones).

Hide DXF layer convention (case-insensitive; read with ezdxf; lengths are
converted to mm from the file's ``$INSUNITS``, unitless files are read as mm):

* ``HIDE`` -- closed outline(s) of the hide(s) (LWPOLYLINE / POLYLINE /
  SPLINE / ELLIPSE / CIRCLE; arcs and splines are flattened).  The material
  outside every zone has grade 1; ``HIDE_<g>`` sets that base grade to g.
* ``DEFECT`` (or ``DEFECT_<anything>``) -- closed regions no part may overlap
  (holes, scars, brands), kept ``margin`` mm away from parts.
* ``ZONE_<g>`` -- closed quality zones of grade g (integer, higher = better,
  or a letter A-D = 4-1 as in :mod:`core.dxfimport.grades`).
  Where zones nest, the smallest zone containing a point decides its grade.

A part of grade p may only lie where the grade is >= p (grade 0 parts go
anywhere on the hide).  Each defect or zone belongs to the hide outline that
contains its first vertex; several hides in one file are nested in the order
of their outlines' leftmost points.
"""

from __future__ import annotations

import re
from typing import List, Optional, Sequence, Tuple

import numpy as np
from shapely.geometry import MultiPolygon, Polygon
from shapely.geometry.base import BaseGeometry
from shapely.ops import unary_union
from shapely.strtree import STRtree

from ..errors import InputError
from ..geometry import Point
from ..model import Container

_ZONE = re.compile(r"^ZONE_(-?\d+|[A-D])$", re.I)
_HIDE = re.compile(r"^HIDE(?:_(-?\d+|[A-D]))?$", re.I)


def _grade(text: str) -> int:
    from ..dxfimport.grades import LETTERS
    return LETTERS[text.upper()] if text.upper() in LETTERS else int(text)


def rectangle(x0: float, y0: float, x1: float, y1: float) -> List[Point]:
    return [(x0, y0), (x1, y0), (x1, y1), (x0, y1)]


def _ccw(ring: Sequence[Point]) -> List[Point]:
    """``ring`` (not closed, positive area) counter-clockwise, as float pairs
    (the shoelace sign: a shapely Polygon per ring cost 0.4 s of preparing
    Baldacci Test10's 10 hides)."""
    pts = [(float(x), float(y)) for x, y in ring]
    if len(pts) > 1 and pts[0] == pts[-1]:
        pts = pts[:-1]
    a = np.asarray(pts)
    area2 = float(np.dot(a[:, 0], np.roll(a[:, 1], -1)) - np.dot(np.roll(a[:, 0], -1), a[:, 1]))
    return pts if area2 > 0 else pts[::-1]


def read_hide_dxf(path: str, flatten_tol: float = 0.1) -> List[Container]:
    """Hides in a DXF drawn with the layer convention above."""
    import ezdxf
    from ezdxf import path as ezpath

    try:
        doc = ezdxf.readfile(path)
    except IOError as exc:
        raise InputError(f"cannot read hide DXF: {exc}", path) from None
    except ezdxf.DXFStructureError as exc:
        raise InputError(f"not a valid DXF file: {exc}", path) from None
    from ezdxf import units as ezunits
    try:
        factor = ezunits.conversion_factor(doc.units, ezunits.MM) if doc.units else 1.0
    except (KeyError, ValueError, TypeError):
        factor = 1.0
    outlines: List[Tuple[int, List[Point], str]] = []
    defects: List[Tuple[List[Point], str]] = []
    zones: List[Tuple[int, List[Point], str]] = []
    for e in doc.modelspace():
        layer = e.dxf.get("layer", "0").upper()
        hm, zm = _HIDE.match(layer), _ZONE.match(layer)
        is_defect = layer == "DEFECT" or layer.startswith("DEFECT_")
        if not (hm or zm or is_defect):
            continue
        src = f"{path}: {e.dxftype()} #{e.dxf.handle} on layer {layer}"
        try:
            p = ezpath.make_path(e)
        except (TypeError, ValueError):
            raise InputError("entity cannot be a closed region", src) from None
        pts = [(v.x * factor, v.y * factor) for v in p.flattening(flatten_tol / factor)]
        closed = getattr(e, "closed", None) or e.dxftype() == "CIRCLE" or \
            (len(pts) > 2 and abs(pts[0][0] - pts[-1][0]) + abs(pts[0][1] - pts[-1][1]) < 1e-6)
        if e.dxftype() == "POLYLINE":
            closed = e.is_closed
        if not closed or len(pts) < 3:
            raise InputError("region outline is not closed", src)
        if len(pts) > 1 and pts[0] == pts[-1]:
            pts = pts[:-1]
        poly = Polygon(pts)
        if not poly.is_valid or poly.area <= 0:
            raise InputError("region outline crosses itself or has no area", src)
        ring = _ccw(pts)
        if hm:
            outlines.append((_grade(hm.group(1)) if hm.group(1) else 1, ring, src))
        elif zm:
            zones.append((_grade(zm.group(1)), ring, src))
        else:
            defects.append((ring, src))
    if not outlines:
        raise InputError("no hide outline: draw it as a closed polyline on layer HIDE", path)
    outlines.sort(key=lambda o: (min(x for x, _ in o[1]), min(y for _, y in o[1])))
    hides = [Container(id=f"hide{i + 1}", kind="hide", outline=o[1], base_grade=o[0])
             for i, o in enumerate(outlines)]
    polys = [Polygon(o[1]) for o in outlines]

    def owner(ring: List[Point], src: str) -> Container:
        from shapely.geometry import Point as SPoint
        for h, pg in zip(hides, polys):
            if pg.intersects(SPoint(ring[0])) or pg.intersects(Polygon(ring)):
                return h
        raise InputError("region lies outside every hide outline", src)

    for ring, src in defects:
        owner(ring, src).defects.append(ring)
    for g, ring, src in zones:
        owner(ring, src).zones.append((g, ring))
    return hides


def zone_pieces(c: Container) -> List[Tuple[int, BaseGeometry]]:
    """(grade, where that zone decides the grade) for every zone of ``c``:
    the zone minus the zones smaller than it (the smallest zone containing a
    point decides; equal areas: the later one in ``c.zones``)."""
    zs = sorted(((zg, Polygon(ring)) for zg, ring in c.zones), key=lambda z: -z[1].area)
    if not zs:
        return []
    tree = STRtree([zp for _zg, zp in zs])
    out = []
    for i, (zg, zp) in enumerate(zs):
        smaller = [zs[j][1] for j in sorted(int(j) for j in tree.query(zp, predicate="intersects"))
                   if j > i and not zp.touches(zs[j][1])]
        out.append((zg, zp.difference(unary_union(smaller)) if smaller else zp))
    return out


def usable_region(c: Container, grade: int,
                  pieces: Optional[List[Tuple[int, BaseGeometry]]] = None) -> BaseGeometry:
    """Where a part of ``grade`` may lie on container ``c`` (no margins): the
    outline minus defects, restricted to zones of that grade or better.
    (One union per kind instead of one set operation per zone and defect:
    a Baldacci Test10 hide, ~40 zones and ~45 holes, 5 grades, took 0.2 s.)
    ``pieces``: ``zone_pieces(c)`` when the caller has it (one per hide)."""
    outline = Polygon(c.outline)
    if pieces is None:
        pieces = zone_pieces(c)
    if c.base_grade >= grade:
        bad = [zp for zg, zp in pieces if zg < grade]
        region: BaseGeometry = outline.difference(unary_union(bad)) if bad else outline
    else:
        region = unary_union([zp for zg, zp in pieces if zg >= grade]).intersection(outline)
    if c.defects:
        region = region.difference(unary_union([Polygon(d) for d in c.defects]))
    return region


def net_area(c: Container) -> float:
    """Outline area minus defects (mm^2); overlapping defects count once."""
    g = Polygon(c.outline)
    if not c.defects:
        return g.area
    return g.difference(unary_union([Polygon(d) for d in c.defects])).area


def polygons_of(g: BaseGeometry) -> List[Polygon]:
    if g.is_empty:
        return []
    if isinstance(g, Polygon):
        return [g]
    if isinstance(g, MultiPolygon):
        return list(g.geoms)
    return [p for p in getattr(g, "geoms", []) if isinstance(p, Polygon)]


def shrink_for_margin(c: Container, grade: int, margin: float, simplify: float = 0.25,
                      pieces: Optional[List[Tuple[int, BaseGeometry]]] = None,
                      usable: Optional[BaseGeometry] = None,
                      ) -> Tuple[List[List[Point]], List[List[Point]], Optional[BaseGeometry]]:
    """The hide region for ``grade`` as (outer rings, obstacle rings) in mm for
    the parts' true shapes: the material shrunk by ``margin`` from the outline
    and the defects (zone borders need no margin), then simplified to fewer
    vertices inside a ``simplify`` mm band (shrunk first, so it never grows).
    ``pieces``: as for :func:`usable_region`; ``usable``: that region of
    ``grade`` when the caller has it."""
    outline = Polygon(c.outline)
    region = usable if usable is not None else usable_region(c, grade, pieces)
    inner = outline.buffer(-margin, 16) if margin > 0 else outline
    region = region.intersection(inner)
    for d in c.defects:
        if margin > 0:
            region = region.difference(Polygon(d).buffer(margin, 16))
    if simplify > 0 and not region.is_empty:
        region = region.buffer(-simplify, 4, join_style=2).simplify(simplify * 0.9)
    outers: List[List[Point]] = []
    holes: List[List[Point]] = []
    for p in polygons_of(region):
        outers.append(_ccw(list(p.exterior.coords)[:-1]))
        for r in p.interiors:
            holes.append(_ccw(list(r.coords)[:-1]))
    return outers, holes, region
