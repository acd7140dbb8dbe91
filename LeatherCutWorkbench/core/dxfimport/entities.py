"""Primitive DXF entities -> drawing-model edges, marks and texts (mm).

Each converter takes the entity, the :data:`~.transform.Affine` from its
coordinates to world mm, its :class:`EdgeSource` and the :class:`Collector`
that receives the results.  INSERT explosion lives in :mod:`.blocks`; what is
not convertible is listed in :data:`SKIP_REASONS` (or reported as unknown).
"""

from __future__ import annotations

import math
from collections import Counter
from typing import Any, Callable, Dict, List, Tuple

from ezdxf.math import OCS

from ..errors import InputError
from ..model import EdgeSource, Finding, LineEdge, Mark, SplineEdge, TextNote
from .limits import MAX_COORDINATE_MM
from .transform import TWO_PI, Affine, apply, bulge_arc, conic_edge, length_scale

#: Findings quoted per (entity type, reason); the rest are summarised.
MAX_FINDINGS_PER_KIND = 20

#: Entity types skipped on purpose -> (level, reason).
SKIP_REASONS: Dict[str, Tuple[str, str]] = {
    **{t: ("warning", "3-D entity: no 2-D cut geometry") for t in
       ("3DFACE", "3DSOLID", "REGION", "BODY", "MESH", "SURFACE", "EXTRUDEDSURFACE",
        "LOFTEDSURFACE", "REVOLVEDSURFACE", "SWEPTSURFACE", "PLANESURFACE", "POLYFACE",
        "POLYMESH")},
    **{t: ("warning", "filled area: not converted (draw its outline as lines to cut it)") for t in
       ("HATCH", "SOLID", "TRACE", "WIPEOUT", "MPOLYGON")},
    **{t: ("info", "dimension/annotation object: not cut geometry") for t in
       ("DIMENSION", "ARC_DIMENSION", "LARGE_RADIAL_DIMENSION", "LEADER", "MULTILEADER",
        "MLEADER", "TOLERANCE", "ACAD_TABLE", "ACAD_PROXY_ENTITY")},
    "MLINE": ("warning", "MLINE (multiline) is not converted: explode it in the CAD program"),
    "XLINE": ("warning", "infinite construction line (XLINE): ignored, not in extents"),
    "RAY": ("warning", "infinite construction line (RAY): ignored, not in extents"),
    **{t: ("info", "raster image / underlay: not cut geometry") for t in
       ("IMAGE", "PDFUNDERLAY", "DWFUNDERLAY", "DGNUNDERLAY", "OLE2FRAME", "OLEFRAME")},
    "SHAPE": ("info", "SHAPE (font glyph) is not converted"),
    "ATTDEF": ("info", "attribute definition (template; values come from the INSERT's ATTRIBs)"),
    "VIEWPORT": ("info", "viewport: not geometry"),
}


class Collector:
    """Receives converted geometry and remembers what was skipped and noted.

    ``converted`` counts entities converted by type; ``exploded`` counts every
    entity met after replacing INSERTs by their blocks (converted or not);
    ``skipped`` counts (type, reason)."""

    def __init__(self, path: str):
        self.path = path
        self.edges: List[Any] = []
        self.marks: List[Mark] = []
        self.texts: List[TextNote] = []
        self.converted: Counter = Counter()
        self.exploded: Counter = Counter()
        self.skipped: Counter = Counter()
        self.skipped_list: List[Dict[str, Any]] = []
        self.findings: List[Finding] = []
        self._notes: Dict[str, Tuple[str, List[str]]] = {}

    def skip(self, e: Any, level: str, reason: str, block: str = "") -> None:
        """Record a skipped entity; a Finding names its handle, type and layer."""
        dxftype = e.dxftype()
        handle = e.dxf.get("handle") or "?"
        layer = e.dxf.get("layer", "0")
        key = (dxftype, reason)
        self.skipped[key] += 1
        where = f" in block {block}" if block else ""
        if self.skipped[key] <= MAX_FINDINGS_PER_KIND:
            self.skipped_list.append({"handle": handle, "type": dxftype, "layer": layer,
                                      "block": block, "reason": reason})
            self.findings.append(Finding(level, "skipped-entity",
                                         f"{dxftype} #{handle} on layer {layer!r}{where} "
                                         f"skipped: {reason}", f"{self.path}#{handle}"))

    def note(self, code: str, message: str, handle: str) -> None:
        """Collect handles for one summarised Finding per ``code``."""
        entry = self._notes.setdefault(code, (message, []))
        entry[1].append(handle)

    def finish(self) -> None:
        """Turn summaries (skips beyond the quota, notes) into Findings."""
        for (dxftype, reason), n in sorted(self.skipped.items()):
            if n > MAX_FINDINGS_PER_KIND:
                self.findings.append(Finding(
                    "warning", "skipped-entity",
                    f"{n - MAX_FINDINGS_PER_KIND} more {dxftype} entities skipped ({reason}); "
                    f"{n} in total", self.path))
        for code, (message, handles) in self._notes.items():
            shown = ", ".join(f"#{h}" for h in handles[:10])
            more = f" and {len(handles) - 10} more" if len(handles) > 10 else ""
            self.findings.append(Finding("info", code, f"{message}: {len(handles)} entities "
                                         f"({shown}{more})", self.path))


_Z = (0.0, 0.0, 1.0)


def _is_z(ex: Any) -> bool:
    return ex[0] == 0.0 and ex[1] == 0.0 and ex[2] > 0.0


def _extrusion(e: Any) -> Any:
    """The entity's extrusion vector; read from the attributes present in the
    file (``vars``) because ezdxf's default lookup is slow for absent ones."""
    return vars(e.dxf).get("extrusion", _Z)


def line(e: Any, t: Affine, src: EdgeSource, out: Collector) -> None:
    dxf = e.dxf
    out.edges.append(LineEdge(apply(t, dxf.start), apply(t, dxf.end), src))


def _circle(e: Any, t: Affine, src: EdgeSource, out: Collector, t_start: float, span: float) -> None:
    dxf = e.dxf
    r = dxf.radius
    if not r > 0.0:
        out.skip(e, "warning", f"radius {r} is not positive", src.block)
        return
    if r > MAX_COORDINATE_MM:      # its square overflows: it would look edge-on
        raise InputError(f"{e.dxftype()} #{e.dxf.get('handle') or '?'}: radius {r:g} is beyond "
                         f"the coordinate limit of {MAX_COORDINATE_MM:.0e} mm", out.path)
    ex = _extrusion(e)
    if _is_z(ex):
        center, u, v = dxf.center, (r, 0.0, 0.0), (0.0, r, 0.0)
    else:  # OCS: e.g. extrusion (0,0,-1) from mirrored blocks mirrors x
        ocs = OCS(ex)
        center, u, v = ocs.to_wcs(dxf.center), ocs.ux * r, ocs.uy * r
    edge = conic_edge(t, center, u, v, t_start, span, src)
    if edge is None:
        out.skip(e, "warning", "curve is seen edge-on in the XY plane (tilted OCS)", src.block)
    else:
        out.edges.append(edge)


def circle(e: Any, t: Affine, src: EdgeSource, out: Collector) -> None:
    _circle(e, t, src, out, 0.0, TWO_PI)


def arc(e: Any, t: Affine, src: EdgeSource, out: Collector) -> None:
    dxf = e.dxf
    a1 = dxf.start_angle % 360.0
    span = (dxf.end_angle - dxf.start_angle) % 360.0
    if span == 0.0:
        out.skip(e, "warning", "start and end angle are equal (zero-length arc)", src.block)
        return
    _circle(e, t, src, out, math.radians(a1), math.radians(span))


def ellipse(e: Any, t: Affine, src: EdgeSource, out: Collector) -> None:
    dxf = e.dxf
    major, ratio = dxf.major_axis, dxf.ratio
    if not (major[0] or major[1] or major[2]) or not 0.0 < ratio <= 1.0:
        out.skip(e, "warning", f"ellipse with major axis {tuple(major)} and ratio {ratio} is "
                 f"degenerate (the ratio must lie in (0, 1])", src.block)
        return
    p1 = dxf.start_param
    span = (dxf.end_param - p1) % TWO_PI
    if span <= 1e-12 or abs(span - TWO_PI) <= 1e-12:
        span = TWO_PI
    edge = conic_edge(t, dxf.center, major, e.minor_axis, p1, span, src)
    if edge is None:
        out.skip(e, "warning", "ellipse is degenerate or seen edge-on in the XY plane", src.block)
    else:
        out.edges.append(edge)


def _polyline_2d(e: Any, pts: List[Tuple[float, float, float]], closed: bool, elevation: float,
                 ex: Any, t: Affine, src: EdgeSource, out: Collector) -> None:
    """Edges of a 2-D polyline given as (x, y, bulge) in its OCS."""
    n = len(pts)
    if n < 2:
        out.skip(e, "info", f"polyline with {n} vertex: nothing to cut", src.block)
        return
    if _is_z(ex):
        to_wcs = None
        ux, uy = (1.0, 0.0, 0.0), (0.0, 1.0, 0.0)
    else:
        ocs = OCS(ex)
        to_wcs = ocs.to_wcs
        ux, uy = ocs.ux, ocs.uy
    edges = out.edges
    a, b, c, tx, d, e_, f, ty = t
    world = []
    for x, y, _ in pts:
        p = (x, y, elevation) if to_wcs is None else to_wcs((x, y, elevation))
        world.append((a * p[0] + b * p[1] + c * p[2] + tx, d * p[0] + e_ * p[1] + f * p[2] + ty))
    last = n if closed else n - 1
    for i in range(last):
        j = i + 1 if i + 1 < n else 0
        bulge = pts[i][2]
        if bulge == 0.0 or pts[i][0] == pts[j][0] and pts[i][1] == pts[j][1]:
            edges.append(LineEdge(world[i], world[j], src))
            continue
        (cx, cy), r, start, sweep = bulge_arc(pts[i], pts[j], bulge)
        centre = (cx, cy, elevation) if to_wcs is None else to_wcs((cx, cy, elevation))
        edge = conic_edge(t, centre, (ux[0] * r, ux[1] * r, ux[2] * r),
                          (uy[0] * r, uy[1] * r, uy[2] * r), start, sweep, src)
        edges.append(edge if edge is not None else LineEdge(world[i], world[j], src))


def _lw_rows(e: Any) -> List[List[float]]:
    """LWPOLYLINE vertices as [x, y, start width, end width, bulge] (OCS)."""
    values = getattr(e.lwpoints, "values", None)
    if values is not None and hasattr(values, "tolist"):  # ezdxf >= 1.1: (n, 5) array, fast
        return values.tolist()
    return [list(p) for p in e.get_points("xyseb")]


def lwpolyline(e: Any, t: Affine, src: EdgeSource, out: Collector) -> None:
    attrs = vars(e.dxf)
    rows = _lw_rows(e)
    if attrs.get("const_width") or any(r[2] or r[3] for r in rows):
        out.note("width-ignored", "polyline width ignored (the centre line is cut)",
                 attrs.get("handle") or "?")
    _polyline_2d(e, [(r[0], r[1], r[4]) for r in rows], e.closed, attrs.get("elevation", 0.0),
                 attrs.get("extrusion", _Z), t, src, out)


def polyline(e: Any, t: Affine, src: EdgeSource, out: Collector) -> None:
    mode = e.get_mode()
    handle = e.dxf.get("handle", "?")
    if mode in ("AcDbPolyFaceMesh", "AcDbPolygonMesh"):
        out.skip(e, "warning", "3-D mesh polyline: no 2-D cut geometry", src.block)
        return
    # vertices flagged 16 are the control frame of a spline-fit polyline, not the curve
    verts = [v for v in e.vertices if not v.dxf.get("flags", 0) & 16]
    if mode == "AcDb3dPolyline":
        pts = [apply(t, v.dxf.location) for v in verts]
        if len({round(v.dxf.location[2], 9) for v in verts}) > 1:
            out.note("projected-3d", "3-D polyline projected onto XY", handle)
        n = len(pts)
        if n < 2:
            out.skip(e, "info", f"polyline with {n} vertex: nothing to cut", src.block)
            return
        pairs = list(zip(pts, pts[1:])) + ([(pts[-1], pts[0])] if e.is_closed else [])
        out.edges.extend(LineEdge(p, q, src) for p, q in pairs)
        return
    dxf = e.dxf
    if dxf.get("default_start_width", 0.0) or dxf.get("default_end_width", 0.0) or any(
            v.dxf.get("start_width", 0.0) or v.dxf.get("end_width", 0.0) for v in verts):
        out.note("width-ignored", "polyline width ignored (the centre line is cut)", handle)
    pts = [(v.dxf.location[0], v.dxf.location[1], v.dxf.get("bulge", 0.0)) for v in verts]
    _polyline_2d(e, pts, e.is_closed, dxf.elevation[2], _extrusion(e), t, src, out)


def spline(e: Any, t: Affine, src: EdgeSource, out: Collector) -> None:
    """True B-spline: poles, full knot vector, weights (affine maps act on poles)."""
    try:
        tool = e.construction_tool()
    except Exception as exc:  # ezdxf raises various errors for broken splines
        out.skip(e, "warning", f"invalid SPLINE definition ({exc})", src.block)
        return
    from_fit = len(e.control_points) == 0
    if from_fit:
        out.note("spline-from-fit-points", "SPLINE given by fit points only: control points "
                 "re-interpolated by ezdxf (may differ slightly from the CAD program's curve)",
                 e.dxf.get("handle", "?"))
    poles = [apply(t, p) for p in tool.control_points]
    weights = [float(w) for w in tool.weights()] if tool.is_rational else []
    out.edges.append(SplineEdge(poles, [float(k) for k in tool.knots()], weights,
                                int(tool.degree), bool(e.closed), from_fit, src))


def point(e: Any, t: Affine, src: EdgeSource, out: Collector, kind: str = "point") -> None:
    out.marks.append(Mark(apply(t, e.dxf.location), kind, src))


def text(e: Any, t: Affine, src: EdgeSource, out: Collector) -> None:
    dxf = e.dxf
    ex = _extrusion(e)
    pos = dxf.insert if _is_z(ex) else OCS(ex).to_wcs(dxf.insert)
    out.texts.append(TextNote(e.plain_text(), apply(t, pos), dxf.get("height", 0.0) * length_scale(t), src))


def mtext(e: Any, t: Affine, src: EdgeSource, out: Collector) -> None:
    dxf = e.dxf
    out.texts.append(TextNote(e.plain_text(split=False), apply(t, dxf.insert),
                              dxf.get("char_height", 0.0) * length_scale(t), src))


#: Converters of edge-producing entity types.
EDGE_CONVERTERS: Dict[str, Callable[[Any, Affine, EdgeSource, Collector], None]] = {
    "LINE": line, "ARC": arc, "CIRCLE": circle, "ELLIPSE": ellipse,
    "LWPOLYLINE": lwpolyline, "POLYLINE": polyline, "SPLINE": spline,
}
#: Converters of annotation entity types (TEXT-like).
TEXT_CONVERTERS: Dict[str, Callable[[Any, Affine, EdgeSource, Collector], None]] = {
    "TEXT": text, "MTEXT": mtext, "ATTRIB": text,
}


def skip_reason(dxftype: str) -> Tuple[str, str]:
    """(level, reason) for an entity type no converter handles."""
    return SKIP_REASONS.get(dxftype, ("warning", f"entity type {dxftype} is not supported"))

