"""Common-edge clusters -> cells, with FreeCAD's planar arrangement.

A connected group of edges with a node of degree > 2 (parts sharing edges, drawn
as separate outlines or as single lines with T-junctions) is cut into all the
regions its edges bound: a rectangle face a little larger than the group is split
by ``generalFuse`` with the edges (the only FreeCAD call that is right on such
layouts — wire-sorting calls return the group outline plus open middle lines).
The cell touching the rectangle is the outside and is dropped; each other cell's
``OuterWire`` is one contour (a dangling edge inside a cell survives as an inner
wire and is ignored).  Edges on no cell boundary are returned as leftovers.

Evidence for over-recognition is computed per cell here because only here is
the map from drawn edges to their split pieces known:

* ``drawn``: some piece of the cell boundary belongs to a drawn entity (same
  DXF handle, or the same edge when handles are unknown) lying wholly on this
  cell's boundary -- the designer drew (part of) this outline for this region.
  A region none of whose sides was drawn for it, next to regions that were, is
  the leftover between parts (import clean-up may drop one copy of a shared
  edge, so "some" rather than "every" side);
* ``all_shared``: every boundary piece also bounds another cell;
* ``pinwheel``: at every corner the cell's boundary turns off a line that runs
  straight on (degree-3 T-junctions, all in the same rotational sense) -- the
  scrap square left between four parts arranged around it.
"""

from __future__ import annotations

from collections import defaultdict
from typing import Dict, List, Set, Tuple

import FreeCAD
import Part

from ..geometry import Segment
from .from_part import chain, edge_segment, orient
from .graph import Graph
from .loops import Loop
from .to_part import segment_edges

V = FreeCAD.Vector


class Cell:
    """One bounded region of a cluster."""

    def __init__(self, loop: Loop, hashes: List[int]):
        self.loop = loop
        self.hashes = hashes
        self.drawn = False
        self.all_shared = False
        self.pinwheel = False
        self.neighbours: Set[int] = set()


def arrange(graph: Graph, comp: List[int], cluster: int, chord_tol: float,
            fuzzy: float, ident=lambda src: src) -> Tuple[List[Cell], List[Segment]]:
    """Cells of one cluster (component piece indices ``comp``) and the segments
    of edges that bound no cell.  ``ident(src)`` names the drawn entity an edge
    came from (edges of one polyline share it)."""
    pieces, pos = graph.pieces, graph.pos
    edges: List["Part.Edge"] = []
    owner: List[object] = []               # argument index -> drawn entity
    arg_src: List[int] = []                # argument index -> drawing edge index
    for i in comp:
        pc = pieces[i]
        for e in segment_edges(pc.seg, pos[pc.n0], pos[pc.n1], pc.curve):
            edges.append(e)
            owner.append(ident(pc.src))
            arg_src.append(pc.src)
    comp_box = Part.Compound(edges).BoundBox
    m = max(comp_box.XLength, comp_box.YLength) * 0.05 + 1.0
    x0, y0 = comp_box.XMin - m, comp_box.YMin - m
    x1, y1 = comp_box.XMax + m, comp_box.YMax + m
    frame = Part.Face(Part.makePolygon([V(x0, y0, 0), V(x1, y0, 0), V(x1, y1, 0),
                                        V(x0, y1, 0), V(x0, y0, 0)]))
    result, pieces_map = frame.generalFuse(edges, fuzzy)

    # drawn entity -> hashes of the pieces it was split into
    src_hashes: Dict[object, Set[int]] = defaultdict(set)
    hash_src: Dict[int, Set[int]] = defaultdict(set)
    for k, out in enumerate(pieces_map[1:]):
        for e in out:
            h = e.hashCode()
            src_hashes[owner[k]].add(h)
            hash_src[h].add(arg_src[k])

    cells: List[Cell] = []
    used: Set[int] = set()
    for face in result.Faces:
        fb = face.BoundBox
        if fb.XMin <= x0 + 1e-9 or fb.YMin <= y0 + 1e-9 or fb.XMax >= x1 - 1e-9 \
                or fb.YMax >= y1 - 1e-9:
            continue                           # the outside (touches the frame)
        wire = outer_wire(face)
        ordered = wire.OrderedEdges
        hashes = [e.hashCode() for e in ordered]
        used.update(hashes)
        segs = chain([edge_segment(e, chord_tol) for e in ordered])
        segs = orient(segs, True)
        srcs = set().union(*(hash_src.get(h, set()) for h in hashes)) if hashes else set()
        cell_face = Part.Face(wire) if face.Wires and len(face.Wires) > 1 else face
        nodes = {n for n in (graph.grid.find(sg.start) for sg in segs) if n >= 0}
        loop = Loop(segs, srcs, nodes, face=cell_face, cluster=cluster)
        cells.append(Cell(loop, hashes))
    _evidence(cells, src_hashes, result, chord_tol)

    leftovers = [edge_segment(e, chord_tol) for e in result.Edges
                 if e.hashCode() not in used and not _on_frame(e, x0, y0, x1, y1)]
    return cells, leftovers


def outer_wire(face: "Part.Face") -> "Part.Wire":
    """The wire bounding ``face`` from outside.

    ``Face.OuterWire`` is not reliable here: on a cell whose hole touches its
    outer boundary (a part drawn against the sheet border, DeepNest example
    after closing a gap) OCC returned the hole's wire, so the part came out
    twice and the border was lost.  The outer boundary is the wire with the
    largest bounding box, and of wires with the same box the one enclosing the
    most area (mm²)."""
    wires = face.Wires
    if len(wires) == 1:
        return wires[0]

    def size(w) -> "tuple[float, float]":
        b = w.BoundBox
        try:
            enclosed = abs(Part.Face(w).Area)
        except Exception:  # noqa: BLE001 - an open or degenerate wire encloses nothing
            enclosed = 0.0
        return (round(b.XLength * b.YLength, 6), enclosed)
    return max(wires, key=size)


def _on_frame(e: "Part.Edge", x0: float, y0: float, x1: float, y1: float) -> bool:
    b = e.BoundBox
    eps = 1e-7
    return (abs(b.XMin - x0) < eps and abs(b.XMax - x0) < eps) or \
        (abs(b.XMin - x1) < eps and abs(b.XMax - x1) < eps) or \
        (abs(b.YMin - y0) < eps and abs(b.YMax - y0) < eps) or \
        (abs(b.YMin - y1) < eps and abs(b.YMax - y1) < eps)


def _evidence(cells: List[Cell], src_hashes: Dict[object, Set[int]], result,
              chord_tol: float) -> None:
    owners: Dict[int, List[int]] = defaultdict(list)   # piece hash -> cells
    for ci, c in enumerate(cells):
        for h in set(c.hashes):
            owners[h].append(ci)
    by_piece: Dict[int, List[Set[int]]] = defaultdict(list)
    for hs in src_hashes.values():
        for h in hs:
            by_piece[h].append(hs)
    for ci, c in enumerate(cells):
        boundary = set(c.hashes)
        c.drawn = any(any(hs <= boundary for hs in by_piece.get(h, ())) for h in boundary)
        c.all_shared = all(len(owners[h]) > 1 for h in boundary)
        for h in boundary:
            c.neighbours.update(o for o in owners[h] if o != ci)
    _pinwheels(cells, result, chord_tol)


def _pinwheels(cells: List[Cell], result, chord_tol: float) -> None:
    """Set ``pinwheel`` on cells whose every corner is a degree-3 T-junction
    where one of the cell's two sides runs straight on, always the same one
    (incoming or outgoing) going round the cell."""
    # node (quantised) -> headings of all arrangement edges leaving it
    q = 1e-4
    leaving: Dict[Tuple[int, int], List[float]] = defaultdict(list)
    for e in result.Edges:
        s = edge_segment(e, chord_tol)
        leaving[_qp(s.start, q)].append(s.start_heading())
        leaving[_qp(s.end, q)].append(s.end_heading() + 180.0)
    for c in cells:
        if not c.all_shared:
            continue
        segs = c.loop.segs
        senses = set()
        corners = 0
        ok = True
        for i in range(len(segs)):
            a, b = segs[i - 1], segs[i]
            h_in, h_out = a.end_heading(), b.start_heading()
            if _adiff(h_in, h_out) < 1.0:
                continue                                    # straight on: no corner
            corners += 1
            here = leaving.get(_qp(b.start, q), [])
            if len(here) != 3:
                ok = False
                break
            in_goes_on = any(_adiff(h, h_in) < 1.0 for h in here)
            out_came = any(_adiff(h, h_out + 180.0) < 1.0 for h in here)
            if in_goes_on == out_came:
                ok = False
                break
            senses.add(in_goes_on)
        c.pinwheel = ok and corners >= 3 and len(senses) == 1


def _qp(p, q: float) -> Tuple[int, int]:
    return (round(p[0] / q), round(p[1] / q))


def _adiff(a: float, b: float) -> float:
    d = (a - b + 180.0) % 360.0 - 180.0
    return abs(d)
