"""Steps 1-4 of recognition for one group of edges (a drawing or a pattern piece).

Cut edges -> segments (zero-length and duplicated edges dropped) -> graph (end
points snapped, T-junctions and overshoots split, dangling edges peeled into
open chains) -> gap proposals (:func:`build_graph`; the caller numbers their
flags) -> the accepted fixes applied -> closed loops (:func:`build_loops`):
simple cycles directly, components with junctions through FreeCAD's arrangement
(with over-recognition evidence per cell) -> duplicate outlines dropped ->
self-crossing / crossing outlines found.  Lengths mm.
"""

from __future__ import annotations

import math
from collections import defaultdict
from typing import Dict, List, Optional, Set, Tuple

from ..errors import InputError
from ..geometry import LineSeg
from ..model import Drawing, Finding, LineEdge
from .arrangement import arrange
from .flags import GapProposal, gap_proposals, missed_contours
from .graph import Graph, Piece
from .leadins import Chain, chains
from .loops import Loop, edge_key, outline_problems, simple_loop
from .options import RecogniseOptions
from .to_part import describe, to_segment


class Group:
    """One group of edges recognised on its own."""

    def __init__(self, name: Optional[str], indices: List[int], info=None):
        self.name = name
        self.indices = indices
        self.info = info                 # PieceInfo of a pattern piece, else None
        self.crossing: List[Tuple[Loop, str]] = []
        self.overlapping: List[Tuple[Loop, Loop]] = []
        self.loops: List[Loop] = []
        self.chains: List[Chain] = []
        self.gaps: List[GapProposal] = []
        self.misses: List[GapProposal] = []
        self.closed_gaps: List[GapProposal] = []
        self.graph: Optional[Graph] = None
        self.has_grain = False


def build_graph(drawing: Drawing, grp: Group, options: RecogniseOptions,
                findings: List[Finding], step) -> None:
    """Steps 1-3: pieces, graph, chains and gap proposals of one group (nothing
    applied yet: the caller numbers the proposals' flags first)."""
    tol = options.join_tol
    where = f"{drawing.path}" + (f" piece {grp.name!r}" if grp.name else "")
    pieces: List[Piece] = []
    keys: Set[Tuple] = set()
    short = dups = 0
    hypot = math.hypot
    for i in grp.indices:
        e = drawing.edges[i]
        if e.src.role == "grain":
            grp.has_grain = True
        if e.src.role != "cut":
            continue
        if type(e) is LineEdge:
            # to_segment, LineSeg.length and edge_key inlined for the bulk of
            # the edges (a million lines): the same operations, the same floats
            a, b = tuple(e.start), tuple(e.end)
            seg, curve = LineSeg(a, b), None
            if hypot(b[0] - a[0], b[1] - a[1]) < tol:
                short += 1
                continue
            ka = (round(a[0] / tol), round(a[1] / tol))
            kb = (round(b[0] / tol), round(b[1] / tol))
            k = (ka, kb) if ka <= kb else (kb, ka)
            if k in keys:
                dups += 1
                continue
            keys.add(k)
            pieces.append(Piece(i, seg, curve))
            continue
        try:
            seg, curve = to_segment(e, options.chord_tol)
        except InputError as exc:
            findings.append(Finding("warning", "bad-edge", f"edge skipped: {exc.message}",
                                    f"{drawing.path}: {exc.source or describe(e)}"))
            continue
        if seg.length < tol:
            short += 1
            continue
        k = edge_key(seg, tol)
        if k in keys:
            dups += 1
            continue
        keys.add(k)
        pieces.append(Piece(i, seg, curve))
    if short:
        findings.append(Finding("info", "short-edges-dropped",
                                f"{short} cut edges shorter than the join tolerance "
                                f"({tol} mm) dropped", where))
    if dups:
        findings.append(Finding("info", "duplicate-edges-dropped",
                                f"{dups} duplicated cut edges dropped", where))
    step(0.2, "joining end points")
    graph = Graph(pieces, tol, options.chord_tol)
    grp.graph = graph
    graph.split_at_dangling_ends(options.gap_tol)
    graph.peel()
    # a joint inside an open chain may touch an edge (two lead-ins meeting a
    # contour at one point): split there too and peel again
    if graph.split_at_nodes(graph.chain_interior_nodes(), 0.0)[0]:
        graph.peel()
    chain_list = chains(graph)
    grp.gaps = gap_proposals(chain_list, graph, options.gap_tol)
    for gp in grp.gaps:
        for ch in gp.chains:
            ch.kind = "gap"
    grp.misses = missed_contours(chain_list, graph, options.gap_tol)
    for gp in grp.misses:
        gp.chains[0].kind = "gap"
    grp.chains = chain_list


def build_loops(drawing: Drawing, grp: Group, options: RecogniseOptions,
                findings: List[Finding], step) -> None:
    """Step 3b-4: the accepted gap fixes applied (``options.fix_decision`` of each
    proposal's ``flag_id``), then closed loops and the remaining chains."""
    tol = options.join_tol
    where = f"{drawing.path}" + (f" piece {grp.name!r}" if grp.name else "")
    graph = grp.graph
    applied = [gp for gp in grp.gaps + grp.misses if options.fix_decision(gp.flag_id)]
    if applied:
        for k, gp in enumerate(applied):
            for b in gp.bridges:
                graph.add(Piece(-1 - k, b))       # bridges carry source -1 - k
            grp.closed_gaps.append(gp)
        graph.split_at_dangling_ends(0.0)          # a bridge may end on an edge
        graph.peel()
        grp.chains = chains(graph)
        _rebind_proposals(grp, [gp for gp in grp.gaps + grp.misses if gp not in applied])

    step(0.4, "building contours")
    cluster = 0
    comps = graph.components()
    for ci, comp in enumerate(comps):
        if graph.is_simple_cycle(comp):
            grp.loops.append(simple_loop(graph, comp))
            continue
        step(0.4 + 0.4 * ci / len(comps), "splitting common-edge layouts into regions")
        try:
            cells, leftovers = arrange(graph, comp, cluster, options.chord_tol, options.fuzzy,
                                      lambda i: _ident(drawing, i))
        except Exception as exc:  # noqa: BLE001 - OCC failures surface as many types
            findings.append(Finding(
                "warning", "arrangement-failed",
                f"FreeCAD could not split a group of {len(comp)} connected edges into regions "
                f"({type(exc).__name__}: {exc}); its edges are reported as open chains",
                where))
            for i in comp:
                pc = graph.pieces[i]
                grp.chains.append(Chain([pc.seg], -1, -1, [pc.src]))
            continue
        cluster += 1
        grp.loops.extend(_with_evidence(cells, options.gap_tol))
        for seg in leftovers:
            ch = Chain([seg], -1, -1, [])
            grp.chains.append(ch)
    for lp in grp.loops:
        real = [s for s in lp.srcs if s >= 0]
        lp.order = (min(real) if real else 1 << 60, lp.bbox[1], lp.bbox[0])
    grp.loops.sort(key=lambda lp: lp.order)
    for lp in grp.loops:
        lp.chord_tol = options.chord_tol
    _drop_duplicate_loops(grp, tol, findings, where)
    grp.crossing, grp.overlapping = outline_problems(grp.loops)


def _with_evidence(cells, gap_tol: float) -> List[Loop]:
    """Loops of arrangement cells with their over-recognition evidence set."""
    out = []
    for c in cells:
        lp = c.loop
        ev = []
        if not c.drawn and any(cells[j].drawn for j in c.neighbours):
            ev.append("none of its sides was drawn for it (each is part of a longer line or "
                      "of another outline) while the regions around it were drawn as their "
                      "own outlines")
        width = 2.0 * lp.area / max(lp.length, 1e-12)
        if width < gap_tol:
            ev.append(f"a sliver {width:.3g} mm wide on average between nearly coincident lines")
        if c.pinwheel:
            ev.append("every edge is shared and each corner is a T-junction turning off a "
                      "line of a neighbouring part (the gap left between parts around it)")
        if ev:
            lp.auto_over = True
            if c.all_shared:
                ev.append("every edge is shared with a neighbouring part")
        lp.evidence = ev
        out.append(lp)
    return out


def _drop_duplicate_loops(grp: Group, tol: float, findings: List[Finding], where: str) -> None:
    """Closed outlines drawn twice (not edge by edge identical) are kept once:
    same box, and no point of one farther than 10 x join tolerance from the
    other (shapely's Hausdorff distance on the flattened outlines)."""
    import shapely

    q = max(tol * 10, 1e-6)
    buckets: Dict[Tuple, List[Loop]] = defaultdict(list)
    keep = []
    for lp in grp.loops:
        k = tuple(round(v / q) for v in lp.bbox)
        twin = None
        if lp.cluster is None and buckets.get(k):
            here = shapely.LineString(lp.polygon() + lp.polygon()[:1])
            for other in buckets[k]:
                there = shapely.LineString(other.polygon() + other.polygon()[:1])
                if shapely.hausdorff_distance(here, there) <= q:
                    twin = other
                    break
        if twin is not None:
            findings.append(Finding("info", "duplicate-contour",
                                    "a closed outline drawn twice was kept once", where))
            continue
        buckets[k].append(lp)
        keep.append(lp)
    grp.loops = keep


# ----------------------------------------------------------------------
def _ident(drawing: Drawing, i: int):
    """The drawn entity of edge ``i``: its DXF handle, else the edge itself."""
    if i < 0:
        return ("bridge", i)
    h = drawing.edges[i].src.handle
    return ("h", h) if h else ("e", i)


def _rebind_proposals(grp: Group, pending: List[GapProposal]) -> None:
    """After applied fixes re-chained the graph: the proposals left pending
    point at the new chain objects with the same edges (kept as ``gap``
    chains, so they are neither lead-ins nor stubs)."""
    if not pending:
        return
    by_srcs: Dict[Tuple, List[Chain]] = defaultdict(list)
    for ch in grp.chains:
        by_srcs[tuple(sorted(ch.srcs))].append(ch)
    for gp in pending:
        new = []
        for old in gp.chains:
            cands = by_srcs.get(tuple(sorted(old.srcs)), [])
            match = min(cands, key=lambda c: abs(c.length - old.length), default=None)
            if match is None:
                continue
            if gp in grp.misses and match.segs[-1].end != old.segs[-1].end:
                match.reverse()                 # the free end next to the contour last
            match.kind = "gap"
            new.append(match)
        gp.chains = new or gp.chains
