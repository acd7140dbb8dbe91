"""Open chains: walking peeled edges into chains and telling lead-ins from the rest.

A chain is a maximal run of peeled edges through nodes of degree 2.  A chain
with exactly one end on a closed contour and the other end free (touching
nothing) is a lead-in: the knife starts at the free end and enters the contour
where the chain touches it.  When several chains touch one contour, the one whose
direction flows best into the contour's cutting direction is the lead-in and a
chain flowing best out of it is a lead-out.  Everything else stays an open chain.
"""

from __future__ import annotations

import math
from typing import Dict, List, Optional, Sequence, Tuple

from ..geometry import Point, Segment, dist, path_length
from .graph import Graph, oriented
from .nesting_depth import point_in_loop


class Chain:
    """A run of peeled pieces from node ``a`` to node ``b`` (segments oriented)."""

    __slots__ = ("segs", "a", "b", "srcs", "kind", "flag_id", "contour", "id")

    def __init__(self, segs: List[Segment], a: int, b: int, srcs: List[int]):
        self.segs = segs
        self.a = a
        self.b = b
        self.srcs = srcs
        self.kind = "open"          # "open", "lead_in", "lead_out", "overshoot"
        self.flag_id = ""           # its trim flag when an overshoot (stub)
        self.contour: Optional[object] = None
        self.id = ""

    @property
    def length(self) -> float:
        return path_length(self.segs)

    def reverse(self) -> None:
        self.segs = [s.reversed() for s in reversed(self.segs)]
        self.a, self.b = self.b, self.a


def chains(graph: Graph) -> List[Chain]:
    """Split the peeled pieces into chains (ends at nodes of peeled degree != 2
    or at nodes that are on a closed loop)."""
    pieces, adj = graph.pieces, graph.adj
    live = graph.live_degree

    def pdeg(n: int) -> int:
        return sum(1 for j in adj[n] if pieces[j].peeled)

    def stop(n: int) -> bool:
        return live.get(n, 0) > 0 or pdeg(n) != 2

    done = set()
    out: List[Chain] = []
    peeled = [i for i, pc in enumerate(pieces) if pc.peeled]
    # start from stopping nodes first so every chain is walked end to end
    starts: List[Tuple[int, int]] = []
    for i in peeled:
        pc = pieces[i]
        if stop(pc.n0):
            starts.append((i, pc.n0))
        if stop(pc.n1):
            starts.append((i, pc.n1))
    for i, n in starts + [(i, pieces[i].n0) for i in peeled]:
        if i in done:
            continue
        segs: List[Segment] = []
        srcs: List[int] = []
        start = n
        cur, node = i, n
        while True:
            done.add(cur)
            pc = pieces[cur]
            fwd = pc.n0 == node
            segs.append(oriented(pc.seg, fwd))
            srcs.append(pc.src)
            node = pc.n1 if fwd else pc.n0
            if stop(node):
                break
            nxt = [j for j in adj[node] if pieces[j].peeled and j not in done]
            if not nxt:
                break
            cur = nxt[0]
        out.append(Chain(segs, start, node, srcs))
    return out


def classify(chain_list: Sequence[Chain], graph: Graph, node_loops: Dict[int, list],
             gap_tol: float, loops: Sequence, lead_ins: bool = True) -> None:
    """Set ``kind`` and ``contour`` of each still ``open`` chain.  ``node_loops``
    maps a graph node to the loops passing through it (active ones first).  A
    lead-in must touch an active (not excluded) contour and be shorter than it;
    a chain no longer than ``gap_tol`` hanging on a contour is a stub (a line
    running past a corner, or a drawing artefact), never a lead-in: no knife or
    torch enters through a sub-millimetre lead-in.  A lead-in starts on the
    scrap side (outside an outer contour, inside a hole); a line running into
    the part is a slit and stays an open chain.  With ``lead_ins`` False
    (pattern pieces: their open lines on the cut layer are slits, not lead-ins)
    such chains stay open."""
    for ch in chain_list:
        if ch.kind != "open" or ch.a < 0:
            continue
        on_a = bool(node_loops.get(ch.a))
        on_b = bool(node_loops.get(ch.b))
        free_a = graph.degree(ch.a) == 1
        free_b = graph.degree(ch.b) == 1
        if on_a and not on_b and free_b:
            ch.reverse()
            on_a, on_b, free_a, free_b = on_b, on_a, free_b, free_a
        if on_b and not on_a and free_a:
            if ch.length <= gap_tol:
                ch.kind = "overshoot"
                continue
            li = node_loops[ch.b][0]
            lp = loops[li]
            if not lead_ins or lp.excluded or ch.length > lp.length:
                continue
            # the knife comes from the scrap side: outside an outer contour,
            # inside a hole (holes run clockwise); a line into the part is a slit
            if point_in_loop(lp, ch.segs[0].start, graph.tol) != (lp.signed_area < 0):
                continue
            ch.kind = "lead_in"
            ch.contour = li


def assign_lead_outs(by_loop: Dict[int, List[Chain]], loop_segs: Dict[int, List[Segment]]) -> None:
    """Among several chains on one loop (segments in cutting direction), keep the
    best entering chain as lead-in and turn chains that leave in the cutting
    direction into lead-outs (reversed so they start on the contour)."""
    for li, chs in by_loop.items():
        if len(chs) < 2:
            continue
        segs = loop_segs[li]
        scored = []
        for ch in chs:
            p = ch.segs[-1].end
            h_fwd, h_back = _contour_headings(segs, p)
            s_in = math.cos(math.radians(ch.segs[-1].end_heading() - h_fwd))
            s_out = math.cos(math.radians(_rev_start_heading(ch) - h_back))
            scored.append((s_in - s_out, s_in, s_out, ch))
        scored.sort(key=lambda t: -t[0])
        for k, (_, s_in, s_out, ch) in enumerate(scored):
            if k > 0 and s_out > s_in:
                ch.kind = "lead_out"
                ch.reverse()


def _rev_start_heading(ch: Chain) -> float:
    """Heading with which the reversed chain leaves the contour."""
    return ch.segs[-1].reversed().start_heading()


def _contour_headings(segs: Sequence[Segment], p: Point) -> Tuple[float, float]:
    """(heading leaving ``p`` along the contour, heading arriving at ``p``)."""
    best = None
    for i, s in enumerate(segs):
        d = dist(s.start, p)
        if best is None or d < best[0]:
            best = (d, i)
    i = best[1]
    return segs[i].start_heading(), segs[i - 1].end_heading()
