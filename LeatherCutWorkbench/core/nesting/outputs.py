"""Writers for a nested layout: layout JSON, DXF drawing, SVG picture.

All in container coordinates, mm.  The layout JSON schema (``--layout-out``)::

    {"containers": [{"id", "kind", "outline": [[x, y], ...], "defects": [...],
                     "zones": [{"grade", "outline"}]}],
     "items": [{"part", "copy", "container", "angle", "mirrored", "x", "y",
                "polygon": [[x, y], ...], "holes": [[[x, y], ...], ...]}]}

For a strip, x runs along the open length and 0 <= y <= width.  Polygons are
not closed (first vertex not repeated), outer rings CCW, holes CW.

The DXF (ezdxf, R2010, $INSUNITS mm) puts each container on its own offset
(sheets side by side, 10 % apart) with layers ``CONTAINER``, ``DEFECT``,
``ZONE_<g>``, the transformed part contours on ``PARTS`` (one closed LWPOLYLINE
per contour with its arcs as exact bulges, a lone circle as a CIRCLE) and each
copy's id ``<part>#<copy>`` as TEXT on ``LABELS``.

Remnants (``--remnant-out``): the unused material of the hides, written as a
hide DXF the next ``nest --hide`` reads (:func:`remnants`, :func:`write_hide_dxf`).
"""

from __future__ import annotations

import html
import json
import math
from typing import Dict, List, Sequence, Tuple

from shapely.geometry import Polygon

from ..geometry import ArcSeg, LineSeg
from ..model import Container, Contour, Layout, Part
from . import placed_parts


def _ring(points) -> List[List[float]]:
    return [[round(float(x), 6), round(float(y), 6)] for x, y in points]


def layout_json(parts: Sequence[Part], layout: Layout, chord_tol: float = 0.05) -> Dict:
    """The ``--layout-out`` structure (see module doc)."""
    placed = placed_parts(parts, layout)
    items = []
    for pl, pp in zip(layout.placements, placed):
        items.append({"part": pl.part_id, "copy": pl.copy, "container": pl.container,
                      "angle": pl.angle, "mirrored": pl.mirrored, "x": pl.x, "y": pl.y,
                      "polygon": _ring(pp.outer.points(chord_tol)),
                      "holes": [_ring(h.points(chord_tol)) for h in pp.holes]})
    conts = [{"id": c.id, "kind": c.kind, "outline": _ring(c.outline),
              "defects": [_ring(d) for d in c.defects],
              "zones": [{"grade": g, "outline": _ring(z)} for g, z in c.zones]}
             for c in layout.containers]
    return {"containers": conts, "items": items}


def write_layout_json(path: str, parts: Sequence[Part], layout: Layout) -> None:
    with open(path, "w", encoding="utf-8") as fh:
        json.dump(layout_json(parts, layout), fh, indent=1)
        fh.write("\n")


def _offsets(layout: Layout) -> Dict[str, Tuple[float, float]]:
    """Containers side by side along X (10 % gap) so one drawing shows them all."""
    out: Dict[str, Tuple[float, float]] = {}
    x = 0.0
    for c in layout.containers:
        xs = [p[0] for p in c.outline]
        out[c.id] = (x - min(xs), 0.0)
        w = max(xs) - min(xs)
        x += w * 1.1 + 1.0
    return out


def write_dxf(path: str, parts: Sequence[Part], layout: Layout) -> None:
    """Nested drawing: containers, defects, zones and part contours (arcs kept as bulges)."""
    import ezdxf

    doc = ezdxf.new("R2010", setup=False)
    doc.header["$INSUNITS"] = 4
    for name, color in (("CONTAINER", 8), ("DEFECT", 1), ("PARTS", 7), ("LABELS", 3)):
        doc.layers.add(name, color=color)
    msp = doc.modelspace()
    off = _offsets(layout)

    def poly(ring, layer, dx, dy):
        msp.add_lwpolyline([(x + dx, y + dy) for x, y in ring], close=True,
                           dxfattribs={"layer": layer})

    for c in layout.containers:
        dx, dy = off[c.id]
        poly(c.outline, "CONTAINER", dx, dy)
        for d in c.defects:
            poly(d, "DEFECT", dx, dy)
        for g, z in c.zones:
            if f"ZONE_{g}" not in doc.layers:
                doc.layers.add(f"ZONE_{g}", color=5)
            poly(z, f"ZONE_{g}", dx, dy)
    for pl, pp in zip(layout.placements, placed_parts(parts, layout)):
        dx, dy = off.get(pl.container, (0.0, 0.0))
        for cont in pp.contours():
            _add_contour(msp, cont, dx, dy)
        cx, cy = Polygon(pp.outer.points(0.5)).representative_point().coords[0]
        msp.add_text(f"{pp.id}", height=max(1.0, _size(pp) * 0.05),
                     dxfattribs={"layer": "LABELS"}).set_placement((cx + dx, cy + dy))
    doc.saveas(path)


def _size(p: Part) -> float:
    x0, y0, x1, y1 = p.outer.bbox
    return min(x1 - x0, y1 - y0)


def _add_contour(msp, cont: Contour, dx: float, dy: float) -> None:
    """One closed contour as one entity on ``PARTS``: a lone full circle as a
    CIRCLE, else an LWPOLYLINE whose arcs are bulges (exact, tan(sweep / 4))
    and whose curves are flattened (0.01 mm chords).  One entity per contour,
    not per segment: ezdxf spends ~70 us per entity, and a hide layout of
    12 000 segments took 0.8 s quiet, 3 s on a loaded machine."""
    segs = cont.segments
    if len(segs) == 1 and isinstance(segs[0], ArcSeg) and abs(segs[0].sweep) >= 360.0 - 1e-9:
        s = segs[0]
        msp.add_circle((s.center[0] + dx, s.center[1] + dy), s.radius,
                       dxfattribs={"layer": "PARTS"})
        return
    verts: List[Tuple[float, float, float]] = []
    for s in segs:
        if isinstance(s, ArcSeg):
            # a bulge spans less than a full turn: split a 360 deg arc in two
            halves = [s] if abs(s.sweep) < 360.0 - 1e-9 else \
                [ArcSeg(s.center, s.radius, s.start_angle, s.sweep / 2),
                 ArcSeg(s.center, s.radius, s.start_angle + s.sweep / 2, s.sweep / 2)]
            for h in halves:
                x, y = h.start
                verts.append((x + dx, y + dy, math.tan(math.radians(h.sweep) / 4.0)))
        elif isinstance(s, LineSeg):
            verts.append((s.start[0] + dx, s.start[1] + dy, 0.0))
        else:
            verts.extend((x + dx, y + dy, 0.0) for x, y in s.points(0.01)[:-1])
    msp.add_lwpolyline(verts, format="xyb", close=True, dxfattribs={"layer": "PARTS"})


def render_svg(parts: Sequence[Part], layout: Layout, title: str = "") -> str:
    """An SVG picture of the layout (containers side by side, Y up)."""
    off = _offsets(layout)
    xs, ys = [0.0], [0.0]
    for c in layout.containers:
        dx, dy = off[c.id]
        xs += [p[0] + dx for p in c.outline]
        ys += [p[1] + dy for p in c.outline]
    x0, x1, y0, y1 = min(xs), max(xs), min(ys), max(ys)
    w, h = max(x1 - x0, 1e-6), max(y1 - y0, 1e-6)
    pad = 0.02 * max(w, h)
    sw = max(w, h) / 1500.0

    def path(ring, dx, dy):
        return "M " + " L ".join(f"{x + dx:.4f},{y + dy:.4f}" for x, y in ring) + " Z"

    out = [f'<svg xmlns="http://www.w3.org/2000/svg" viewBox="{x0 - pad:.4f} {-(y1 + pad):.4f} '
           f'{w + 2 * pad:.4f} {h + 2 * pad:.4f}" width="1200" height="{1200 * (h + 2 * pad) / (w + 2 * pad):.0f}">',
           f"<title>{html.escape(title or 'LeatherCut nesting')}</title>",
           '<g transform="scale(1,-1)">']
    for c in layout.containers:
        dx, dy = off[c.id]
        out.append(f'<path d="{path(c.outline, dx, dy)}" fill="#f3ead8" stroke="#555" stroke-width="{sw * 2:.4f}"/>')
        for g, z in c.zones:
            out.append(f'<path d="{path(z, dx, dy)}" fill="#d8e4f3" fill-opacity="0.6" stroke="#68a" '
                       f'stroke-width="{sw:.4f}"><title>zone grade {g}</title></path>')
        for d in c.defects:
            out.append(f'<path d="{path(d, dx, dy)}" fill="#d33" fill-opacity="0.7" stroke="none"/>')
    palette = ["#4e79a7", "#f28e2b", "#59a14f", "#b07aa1", "#edc948", "#76b7b2", "#ff9da7", "#9c755f"]
    colour: Dict[str, str] = {}
    for pl, pp in zip(layout.placements, placed_parts(parts, layout)):
        dx, dy = off.get(pl.container, (0.0, 0.0))
        col = colour.setdefault(pl.part_id, palette[len(colour) % len(palette)])
        d = path(pp.outer.points(0.05), dx, dy) + " " + " ".join(path(hh.points(0.05), dx, dy)
                                                                   for hh in pp.holes)
        out.append(f'<path d="{d}" fill="{col}" fill-opacity="0.75" fill-rule="evenodd" '
                   f'stroke="#222" stroke-width="{sw:.4f}"><title>{html.escape(pp.id)} '
                   f'{pl.angle:g} deg{" mirrored" if pl.mirrored else ""}</title></path>')
    out.append("</g></svg>")
    return "\n".join(out) + "\n"


def remnants(parts: Sequence[Part], layout: Layout, spacing: float = 0.0,
             min_fraction: float = 0.05) -> List[Container]:
    """The unused material of every used hide as new hides for the next job.

    Remnant = hide outline minus every placed part grown by ``spacing`` (the
    knife needs its gap there too); each connected piece of at least
    ``min_fraction`` of the hide's area becomes a hide (id
    ``<hide>_r<k>``) with the original base grade, the defects and zones that
    reach into it (clipped), and the enclosed gaps between parts as defects."""
    from shapely.geometry import Polygon as P
    from shapely.ops import unary_union

    from .checker import part_polygon, placed_polygon
    from .containers import polygons_of
    by_id = {p.id: part_polygon(p) for p in parts}
    out: List[Container] = []
    for c in layout.containers:
        if c.kind != "hide":
            continue
        used = [placed_polygon(by_id[pl.part_id], pl.x, pl.y, pl.angle, pl.mirrored)
                for pl in layout.placements if pl.container == c.id]
        hide = P(c.outline)
        taken = unary_union([g.buffer(spacing, 8) if spacing > 0 else g for g in used])
        rest = hide.difference(taken) if used else hide
        k = 0
        for piece in sorted(polygons_of(rest), key=lambda g: -g.area):
            if piece.area < min_fraction * hide.area:
                continue
            k += 1
            shell = P(piece.exterior)
            defects = [_ring(r.coords[:-1]) for r in piece.interiors]
            for d in c.defects:
                for g in polygons_of(P(d).intersection(shell)):
                    defects.append(_ring(g.exterior.coords[:-1]))
            zones = [(zg, _ring(g.exterior.coords[:-1])) for zg, z in c.zones
                     for g in polygons_of(P(z).intersection(shell))]
            out.append(Container(id=f"{c.id}_r{k}", kind="hide",
                                 outline=_ring(shell.exterior.coords[:-1]), defects=defects,
                                 zones=zones, base_grade=c.base_grade))
    return out


def write_hide_dxf(path: str, hides: Sequence[Container]) -> None:
    """Hides as a DXF in the layer convention :func:`containers.read_hide_dxf`
    reads (``HIDE_<base grade>``, ``DEFECT``, ``ZONE_<g>``), mm."""
    import ezdxf

    doc = ezdxf.new("R2010", setup=False)
    doc.header["$INSUNITS"] = 4
    msp = doc.modelspace()

    def poly(ring, layer):
        if layer not in doc.layers:
            doc.layers.add(layer)
        msp.add_lwpolyline([(x, y) for x, y in ring], close=True, dxfattribs={"layer": layer})

    for h in hides:
        poly(h.outline, f"HIDE_{h.base_grade}")
        for d in h.defects:
            poly(d, "DEFECT")
        for g, z in h.zones:
            poly(z, f"ZONE_{g}")
    doc.saveas(path)


def write_svg(path: str, parts: Sequence[Part], layout: Layout, title: str = "") -> None:
    with open(path, "w", encoding="utf-8") as fh:
        fh.write(render_svg(parts, layout, title))
