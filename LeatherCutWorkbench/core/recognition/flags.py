"""Evidence for the two kinds of recognition doubt.

*Under-recognised*: open chains whose free ends can be joined into a closed
outline with bridges no longer than the gap tolerance (a missed end point, a
missing short segment).  Free ends are paired with their mutual nearest free end
(hash grid of gap-tolerance cells); a set of chains is proposed only when the
bridges close a loop that encloses an area.  Also an open chain that stops
short of a contour by at most the gap tolerance (a lead-in that misses).

*Over-recognised*: text of the evidence collected on a contour (see
:mod:`.arrangement` for cells; the enclosing-frame test is here).
"""

from __future__ import annotations

import math
from collections import defaultdict
from typing import Dict, List, Optional, Sequence, Tuple

from ..geometry import LineSeg, Point, Segment, dist
from .from_part import signed_path_area
from .graph import Graph
from .leadins import Chain


class GapProposal:
    """Chains that close with ``bridges`` (LineSegs, mm); ``gap`` the longest."""

    def __init__(self, chains: List[Chain], bridges: List[LineSeg]):
        self.chains = chains
        self.bridges = bridges
        self.gap = max(b.length for b in bridges)
        self.flag_id = ""            # its under-recognition flag (set before loops are built)


def gap_proposals(chain_list: Sequence[Chain], graph: Graph, gap_tol: float) -> List[GapProposal]:
    """Sets of chains that close into a loop with bridges <= ``gap_tol`` mm.

    Free ends (degree-1 nodes) are paired with their mutual nearest free end.
    Bridges are tried shortest first: a bridge whose two ends are already
    connected through chains (and bridges accepted so far) closes a loop -- the
    loop may pass through a node of a closed contour -- and that loop, if it
    encloses an area, is one proposal."""
    if gap_tol <= 0:
        return []
    ends: List[Tuple[int, Point]] = []            # (graph node, point)
    for ch in chain_list:
        if ch.a < 0:
            continue
        for n, p in ((ch.a, ch.segs[0].start), (ch.b, ch.segs[-1].end)):
            if graph.degree(n) == 1:
                ends.append((n, p))
    if not ends:
        return []
    cell = gap_tol
    grid: Dict[Tuple[int, int], List[int]] = defaultdict(list)
    for k, (_, p) in enumerate(ends):
        grid[(math.floor(p[0] / cell), math.floor(p[1] / cell))].append(k)

    def nearest(k: int) -> Optional[int]:
        p = ends[k][1]
        ix, iy = math.floor(p[0] / cell), math.floor(p[1] / cell)
        best = None
        for dx in (-1, 0, 1):
            for dy in (-1, 0, 1):
                for j in grid.get((ix + dx, iy + dy), ()):
                    if j != k:
                        d = dist(p, ends[j][1])
                        if d <= gap_tol and (best is None or d < best[0]):
                            best = (d, j)
        return None if best is None else best[1]

    bridges = []
    for k in range(len(ends)):
        j = nearest(k)
        if j is not None and k < j and nearest(j) == k:
            bridges.append((dist(ends[k][1], ends[j][1]), k, j))
    bridges.sort()
    # chain graph: node -> [(other node, chain index or -1 - bridge index)]
    adj: Dict[int, List[Tuple[int, int]]] = defaultdict(list)
    parent: Dict[int, int] = {}

    def find(x: int) -> int:
        parent.setdefault(x, x)
        while parent[x] != x:
            parent[x] = parent[parent[x]]
            x = parent[x]
        return x

    for ci, ch in enumerate(chain_list):
        if ch.a < 0:
            continue
        adj[ch.a].append((ch.b, ci))
        adj[ch.b].append((ch.a, ci))
        parent[find(ch.a)] = find(ch.b)
    proposals: List[GapProposal] = []
    used_chains: set = set()
    accepted: List[LineSeg] = []
    for _, k, j in bridges:
        na, nb = ends[k][0], ends[j][0]
        seg = LineSeg(ends[k][1], ends[j][1])
        if find(na) != find(nb):
            parent[find(na)] = find(nb)
            bi = len(accepted)
            accepted.append(seg)
            adj[na].append((nb, -1 - bi))
            adj[nb].append((na, -1 - bi))
            continue
        path = _path(adj, nb, na)
        if path is None:
            continue
        ch_ids = [e for e in path if e >= 0]
        if any(c in used_chains for c in ch_ids):
            continue
        segs: List[Segment] = []
        node = nb
        for e in path:
            if e >= 0:
                ch = chain_list[e]
                fwd = ch.a == node
                segs.extend(ch.segs if fwd else [s.reversed() for s in reversed(ch.segs)])
                node = ch.b if fwd else ch.a
            else:
                b = accepted[-1 - e]
                here = segs[-1].end if segs else ends[j][1]
                segs.append(b if dist(b.start, here) <= dist(b.end, here) else b.reversed())
                node = next(o for o, ee in adj[node] if ee == e)
        segs.append(seg)
        if abs(signed_path_area(segs)) <= max(gap_tol * gap_tol, 1e-6):
            continue
        used_chains.update(ch_ids)
        used_bridges = [accepted[-1 - e] for e in path if e < 0] + [seg]
        proposals.append(GapProposal([chain_list[c] for c in ch_ids], used_bridges))
    return proposals


def _path(adj: Dict[int, List[Tuple[int, int]]], src: int, dst: int) -> Optional[List[int]]:
    """Edge ids along a shortest (fewest edges) path from ``src`` to ``dst``."""
    prev: Dict[int, Tuple[int, int]] = {src: (src, 0)}
    queue = [src]
    for n in queue:
        if n == dst:
            break
        for m, e in adj.get(n, ()):
            if m not in prev:
                prev[m] = (n, e)
                queue.append(m)
    if dst not in prev:
        return None
    out = []
    n = dst
    while n != src:
        p, e = prev[n]
        out.append(e)
        n = p
    out.reverse()
    return out


def missed_contours(chain_list: Sequence[Chain], graph: Graph,
                    gap_tol: float) -> List[GapProposal]:
    """Open chains touching nothing whose one end stops at most ``gap_tol`` mm
    short of a closed contour (a lead-in that misses): the bridge runs from that
    end to the nearest contour point.  Chains near contours at both ends and
    stubs no longer than the gap are left alone."""
    out: List[GapProposal] = []
    if gap_tol <= 0:
        return out
    closed = None
    for ch in chain_list:
        if ch.kind != "open" or ch.a < 0 or ch.length <= gap_tol:
            continue
        if graph.degree(ch.a) != 1 or graph.degree(ch.b) != 1:
            continue
        if closed is None:
            closed = graph.closed_edges()
        near_a = closed.nearest(ch.segs[0].start, gap_tol)
        near_b = closed.nearest(ch.segs[-1].end, gap_tol)
        if (near_a is None) == (near_b is None):
            continue
        if near_a is not None:
            ch.reverse()
            near_b = near_a
        d, q = near_b
        if d <= graph.tol:
            continue
        out.append(GapProposal([ch], [LineSeg(ch.segs[-1].end, q)]))
    return out


def frame_evidence(holes_with_islands: int, holes: int) -> Optional[str]:
    """Reason text when a closed outline looks like a sheet border or group
    outline drawn around parts: two or more of its 'holes' hold parts of their
    own (islands) - real parts rarely carry several parts inside their holes."""
    if holes_with_islands >= 2:
        return (f"encloses {holes} closed outlines of which {holes_with_islands} have holes of "
                "their own: looks like a sheet border or group outline, not a part")
    return None
