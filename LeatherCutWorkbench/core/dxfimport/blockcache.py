"""Block definitions converted once, instanced many times.

A block inserted hundreds of times (pattern pieces, nesting parts, symbols)
is converted once in its own coordinates (identity map, projected on XY) and
every further INSERT only maps the cached edges, marks and texts by its 2-D
affine map.  This is exact whenever the INSERT's map does not mix Z into XY
(``c == f == 0`` in the :data:`~.transform.Affine`: any INSERT whose extrusion is
+Z or -Z at every level, i.e. nearly all), because projecting on XY then
commutes with the map.  Blocks whose conversion produced a skip or a note
(degenerate curves, widths, fit-point splines) are not cached so that every
instance reports them; the caller then converts entity by entity.
"""

from __future__ import annotations

import math
from typing import Any, List, Optional, Tuple

from ..model import ArcEdge, EdgeSource, EllipseEdge, LineEdge, Mark, SplineEdge, TextNote
from .entities import EDGE_CONVERTERS, TEXT_CONVERTERS, Collector, point
from .transform import Affine, conic_edge, length_scale

IDENTITY: Affine = (1.0, 0.0, 0.0, 0.0, 0.0, 1.0, 0.0, 0.0)

#: One cached child of a block: (kind, entity, dxftype, own layer, own colour,
#: edges, marks, texts).  kind: "G" geometry, "I" nested INSERT, "X" skipped type.
Item = Tuple[str, Any, str, str, int, list, list, list]


def flat(t: Affine) -> bool:
    """True when Z does not influence XY under ``t`` (cached instancing is exact)."""
    return t[2] == 0.0 and t[6] == 0.0


def compile_block(definition: Any) -> Optional[List[Item]]:
    """Cached items of a block definition, or None when it must not be cached."""
    items: List[Item] = []
    placeholder = EdgeSource()
    for e in definition:
        dxftype = e.dxftype()
        attrs = vars(e.dxf)
        layer, color = attrs.get("layer", "0"), attrs.get("color", 256)
        if dxftype == "INSERT":
            items.append(("I", e, dxftype, layer, color, [], [], []))
            continue
        conv = EDGE_CONVERTERS.get(dxftype) or TEXT_CONVERTERS.get(dxftype)
        if conv is None and dxftype != "POINT":
            items.append(("X", e, dxftype, layer, color, [], [], []))
            continue
        scratch = Collector("")
        if conv is None:
            point(e, IDENTITY, placeholder, scratch)
        else:
            conv(e, IDENTITY, placeholder, scratch)
        scratch.finish()
        if scratch.findings:
            return None
        items.append(("G", e, dxftype, layer, color, scratch.edges, scratch.marks, scratch.texts))
    return items


def map_edge(g: Any, t: Affine, src: EdgeSource) -> Optional[Any]:
    """A cached edge (block coordinates) mapped by the flat affine ``t``."""
    a, b, _, tx, d, e, _, ty = t
    k = type(g)
    if k is LineEdge:
        (x1, y1), (x2, y2) = g.start, g.end
        return LineEdge((a * x1 + b * y1 + tx, d * x1 + e * y1 + ty),
                        (a * x2 + b * y2 + tx, d * x2 + e * y2 + ty), src)
    if k is ArcEdge:
        r = g.radius
        return conic_edge(t, (g.center[0], g.center[1], 0.0), (r, 0.0, 0.0), (0.0, r, 0.0),
                          math.radians(g.start_angle), math.radians(g.sweep), src)
    if k is EllipseEdge:
        mx, my = g.major_axis
        return conic_edge(t, (g.center[0], g.center[1], 0.0), (mx, my, 0.0),
                          (-my * g.ratio, mx * g.ratio, 0.0), g.start_param,
                          g.end_param - g.start_param, src)
    if k is SplineEdge:
        return SplineEdge([(a * x + b * y + tx, d * x + e * y + ty) for x, y in g.poles],
                          g.knots, g.weights, g.degree, g.closed, g.from_fit_points, src)
    raise TypeError(f"unknown edge type {k.__name__}")


def map_mark(m: Mark, t: Affine, kind: str, src: EdgeSource) -> Mark:
    x, y = m.position
    return Mark((t[0] * x + t[1] * y + t[3], t[4] * x + t[5] * y + t[7]), kind, src)


def map_text(n: TextNote, t: Affine, src: EdgeSource) -> TextNote:
    x, y = n.position
    return TextNote(n.text, (t[0] * x + t[1] * y + t[3], t[4] * x + t[5] * y + t[7]),
                    n.height * length_scale(t), src)
