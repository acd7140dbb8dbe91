"""Closed loops: simple cycles of the edge graph -> FreeCAD wires and faces.

A :class:`Loop` holds a closed path (segments, mm) plus what later steps need:
exact signed area, bounding box as a plain tuple (``Shape.BoundBox`` is
recomputed on every access and costs 30x more), its outline flattened within the
chord tolerance, a sample point on the path, and its FreeCAD face, built only
when FreeCAD's classifier has to decide a point closer than the tolerance to the
outline (cells of common-edge clusters come with the face FreeCAD made).
Fast paths: a pure polygon is one ``Part.makePolygon``, a circle one
``Part.makeCircle``; everything else a wire of edges pinned to the graph nodes.
"""

from __future__ import annotations

import math
from typing import Dict, List, Optional, Sequence, Set, Tuple

import FreeCAD
import numpy as np
import Part

from ..geometry import ArcSeg, LineSeg, Point, Segment
from .from_part import signed_path_area
from .graph import Graph, oriented
from .to_part import segment_edges

V = FreeCAD.Vector
BBox = Tuple[float, float, float, float]


class Loop:
    """One closed contour candidate."""

    __slots__ = ("segs", "srcs", "nodes", "signed_area", "area", "bbox", "face",
                 "_edges", "cluster", "order", "evidence", "shared_idx", "keys",
                 "contour_id", "excluded", "auto_over", "_poly", "chord_tol")

    def __init__(self, segs: List[Segment], srcs: Set[int], nodes: Set[int],
                 edges_builder=None, face=None, cluster: Optional[int] = None):
        self.segs = segs
        self.srcs = srcs
        self.nodes = nodes
        if all(type(s) is LineSeg for s in segs):
            self.signed_area, self.bbox = _line_area_bbox(segs)
        else:
            self.signed_area = signed_path_area(segs)
            self.bbox = path_bbox(segs)
        self.area = abs(self.signed_area)
        self.face = face
        self._edges = edges_builder
        self.cluster = cluster
        self.order: Tuple = ()
        self.evidence: List[str] = []
        self.shared_idx: List[int] = []
        self.keys: List[Tuple] = []
        self.contour_id = ""
        self.excluded = False
        self.auto_over = False
        self._poly: Optional[List[Point]] = None
        self.chord_tol = 0.01

    def get_face(self, tol: float) -> Optional["Part.Face"]:
        """The FreeCAD face bounded by this loop (built on first use)."""
        if self.face is None and self._edges is not None:
            self.face = build_face(self._edges(), tol)
            self._edges = None
        return self.face

    def polygon(self) -> List[Point]:
        """The outline flattened within ``chord_tol`` mm (first point not repeated)."""
        if self._poly is None:
            pts: List[Point] = []
            for s in self.segs:
                if type(s) is LineSeg:
                    pts.append(s.start)
                elif type(s) is ArcSeg:
                    pts.extend(_arc_points(s, self.chord_tol))
                else:
                    pts.extend(s.points(self.chord_tol)[:-1])
            self._poly = pts
        return self._poly

    @property
    def length(self) -> float:
        """Length of the outline in mm."""
        return sum(s.length for s in self.segs)

    def sample_point(self) -> Point:
        """A point on the loop away from its first vertex (mid of the longest segment)."""
        segs = self.segs
        if all(type(s) is LineSeg for s in segs):     # LineSeg.length inline, same floats
            lengths = [math.hypot(s.end[0] - s.start[0], s.end[1] - s.start[1]) for s in segs]
            k = lengths.index(max(lengths))           # the first longest, as max(key=)
            return segs[k].point_at(lengths[k] / 2.0)
        seg = max(segs, key=lambda s: s.length)
        return seg.point_at(seg.length / 2.0)


def _arc_points(s: ArcSeg, chord_tol: float) -> List[Point]:
    """Points of an arc whose chords deviate at most ``chord_tol`` mm, without
    the end point (numpy: arcs are the bulk of the points of typical parts)."""
    r = s.radius
    step = 2.0 * math.degrees(math.acos(max(-1.0, 1.0 - chord_tol / r))) if r > chord_tol else 360.0
    n = max(1, int(math.ceil(abs(s.sweep) / max(step, 1e-6))))
    ang = np.radians(s.start_angle + s.sweep * np.arange(n) / n)
    return list(zip((s.center[0] + r * np.cos(ang)).tolist(),
                    (s.center[1] + r * np.sin(ang)).tolist()))


def build_face(edges, tol: float) -> Optional["Part.Face"]:
    """Face of a closed wire or of a ring of edges given in connection order;
    None if FreeCAD cannot close it (containment then falls back to the box)."""
    if isinstance(edges, Part.Wire):
        try:
            return Part.Face(edges)
        except Exception:  # noqa: BLE001 - FreeCAD raises Part.OCCError
            edges = list(edges.Edges)
    try:
        wire = Part.Wire(edges)
        if not wire.isClosed():
            raise ValueError("open")
    except Exception:  # noqa: BLE001 - FreeCAD raises Part.OCCError / ValueError
        wires = Part.Compound(edges).connectEdgesToWires(False, tol).Wires
        closed = [w for w in wires if w.isClosed()]
        if not closed:
            return None
        wire = max(closed, key=lambda w: w.Length)
    try:
        return Part.Face(wire)
    except Exception:  # noqa: BLE001
        return None


def simple_loop(graph: Graph, comp: List[int]) -> Loop:
    """Loop of a component whose nodes all have degree 2."""
    order = graph.walk_cycle(comp)
    pieces, pos = graph.pieces, graph.pos
    segs = [oriented(pieces[i].seg, fwd) for i, fwd in order]
    ends = [((pieces[i].n0, pieces[i].n1) if fwd else (pieces[i].n1, pieces[i].n0))
            for i, fwd in order]
    nodes = {a for a, _ in ends}

    def edges():
        if all(type(s) is LineSeg for s in segs):
            pts = [V(pos[a][0], pos[a][1], 0) for a, _ in ends]
            pts.append(pts[0])
            return Part.makePolygon(pts)
        out: List["Part.Edge"] = []
        for (i, fwd), seg, (a, b) in zip(order, segs, ends):
            out.extend(segment_edges(seg, pos[a], pos[b], pieces[i].curve))
        return out

    return Loop(segs, {pieces[i].src for i, _ in order}, nodes, edges)


def _line_area_bbox(segs: Sequence[LineSeg]) -> Tuple[float, BBox]:
    """``signed_path_area`` and ``path_bbox`` of a closed path of lines in one
    pass (the same operations in the same order: the same floats)."""
    a = 0.0
    xs: List[float] = []
    ys: List[float] = []
    for s in segs:
        (x0, y0), (x1, y1) = s.start, s.end
        a += x0 * y1 - x1 * y0
        xs += (x0, x1)
        ys += (y0, y1)
    return a / 2.0, (min(xs), min(ys), max(xs), max(ys))


def path_bbox(segs: Sequence[Segment]) -> BBox:
    """Exact bounding box (xmin, ymin, xmax, ymax) of lines and arcs, polyline
    box for curves."""
    xs: List[float] = []
    ys: List[float] = []
    for s in segs:
        if isinstance(s, LineSeg):
            xs += (s.start[0], s.end[0])
            ys += (s.start[1], s.end[1])
        elif isinstance(s, ArcSeg):
            pts = [s.start, s.end]
            lo = min(s.start_angle, s.start_angle + s.sweep)
            hi = max(s.start_angle, s.start_angle + s.sweep)
            k = math.ceil(lo / 90.0)
            while k * 90.0 <= hi:
                a = math.radians(k * 90.0)
                pts.append((s.center[0] + s.radius * math.cos(a),
                            s.center[1] + s.radius * math.sin(a)))
                k += 1
            xs += [p[0] for p in pts]
            ys += [p[1] for p in pts]
        else:
            xs += [p[0] for p in s.pts]
            ys += [p[1] for p in s.pts]
    return (min(xs), min(ys), max(xs), max(ys))


def edge_key(seg: Segment, q: float) -> Tuple:
    """Direction-free geometric key of a segment quantised to ``q`` mm: the same
    edge in two contours gets the same key (used to mark shared edges)."""
    if type(seg) is LineSeg:
        (ax, ay), (bx, by) = seg.start, seg.end
        ka = (round(ax / q), round(ay / q))
        kb = (round(bx / q), round(by / q))
        return (ka, kb) if ka <= kb else (kb, ka)
    a, b = seg.start, seg.end
    m = seg.point_at(seg.length / 2.0)
    ka = (round(a[0] / q), round(a[1] / q))
    kb = (round(b[0] / q), round(b[1] / q))
    return (min(ka, kb), max(ka, kb), round(m[0] / q), round(m[1] / q))


def mark_shared(loops: Sequence[Loop], q: float) -> None:
    """Fill ``shared_idx`` of each active loop: indices of segments whose key
    occurs in another active loop.  Only cells of common-edge clusters can share
    edges (two simple loops sharing an edge would have been one cluster)."""
    count: Dict[Tuple, int] = {}
    loops = [lp for lp in loops if lp.cluster is not None]   # simple loops share nothing
    for lp in loops:
        lp.keys = [edge_key(s, q) for s in lp.segs]
        if lp.excluded:
            continue
        for k in set(lp.keys):
            count[k] = count.get(k, 0) + 1
    for lp in loops:
        lp.shared_idx = ([] if lp.excluded else
                         [i for i, k in enumerate(lp.keys) if count.get(k, 0) > 1])


def outline_problems(loops: Sequence[Loop]) -> Tuple[List[Tuple[Loop, str]],
                                                    List[Tuple[Loop, Loop]]]:
    """Outlines a cutter cannot follow as drawn, found with shapely on the
    flattened outlines: loops crossing themselves (a figure eight drawn without
    a node at the crossing; with shapely's reason text, e.g. the point) and
    pairs of loops crossing each other (overlapping interiors, neither inside
    the other; overlaps below 1 mm^2 or 1 % of the smaller area, or above 99 %,
    are touching or nearly nested outlines and not reported)."""
    import shapely

    cands = [lp for lp in loops if len(lp.polygon()) >= 3]
    if not cands:
        return [], []
    rings = [lp.polygon() for lp in cands]
    coords = np.array([p for ring in rings for p in ring], dtype=float)
    index = np.repeat(np.arange(len(rings)), [len(r) for r in rings])
    polys = shapely.polygons(shapely.linearrings(coords, indices=index))
    valid = shapely.is_valid(polys)
    crossing = [(cands[i], shapely.is_valid_reason(polys[i])) for i in np.flatnonzero(~valid)]
    ok = polys[np.flatnonzero(valid)]
    okc = [cands[i] for i in np.flatnonzero(valid)]
    # box-overlapping pairs from the tree, then one vectorised predicate call
    # (a tree query with the predicate is 20x slower, measured)
    a, b = shapely.STRtree(ok).query(ok)
    keep = a < b
    a, b = a[keep], b[keep]
    hit = np.flatnonzero(shapely.overlaps(ok[a], ok[b])) if len(a) else []
    pairs = []
    for k in hit:
        pa, pb = ok[a[k]], ok[b[k]]
        small = min(shapely.area(pa), shapely.area(pb))
        common = shapely.area(shapely.intersection(pa, pb))
        # touching or nearly nested outlines overlap by slivers: not a crossing
        if max(1.0, 0.01 * small) <= common <= 0.99 * small:
            pairs.append((okc[a[k]], okc[b[k]]))
    return crossing, pairs
