"""From parts to cut items: entry candidates, precedence and common edges.

A *plan item* is what the knife cuts in one go: a closed contour (entered at
one of its candidates, or through one of its lead-ins), an open chain, or a
run of a contour left after its common edges were dropped.  Precedence
(``preds``: indices of items that must be cut first):

* every hole of a part before the part's outline;
* a part lying inside a hole of another part (``Part.parent_id``, or found by
  geometry) before that hole -- the hole's slug carries it -- and so before
  the outer part;
* an open chain lying inside a closed contour before the smallest such
  contour;
* the contour that keeps a common edge before the runs of the contour that
  dropped it (the edge is then cut once, by the item cut first).

A lead-in is part of its contour's item (cut first, from its free end), so
"lead-in before contour" holds by construction.
"""

from __future__ import annotations

from dataclasses import dataclass, field
from typing import Dict, List, Optional, Sequence, Tuple

from ..geometry import (LineSeg, Point, Segment, dist, reverse_path,
                        rotate_closed_path)
from ..model import CutItem, Finding, LeadIn, OpenChain, Part
from .candidates import entry_positions, locate
from .common_edges import edges_to_drop, match_shared, open_runs
from .knife import lift_indices
from .precedence import repair

JOIN_TOL = 1e-6


@dataclass
class Cand:
    """One way to cut an item: head arrives at ``start``, leaves at ``end``.
    ``mode``: ``closed`` (value = arc length of the entry, mm), ``lead_in`` /
    ``lead_out`` (value = index of the lead), ``open`` (value 1 = reversed)."""

    start: Point
    end: Point
    mode: str
    value: float


@dataclass
class PlanItem:
    contour_id: str
    part_id: str
    kind: str                      # hole | outer | open
    segments: List[Segment]
    closed: bool
    lead_ins: List[LeadIn] = field(default_factory=list)
    lead_outs: List[LeadIn] = field(default_factory=list)
    cands: List[Cand] = field(default_factory=list)
    partial: bool = False          # a run of a contour whose common edges were dropped

    def realise(self, cand: Cand, lift_angle: Optional[float]) -> CutItem:
        """The cut item for candidate ``cand``: connected segments in cutting
        order, lead-in first."""
        lead: List[Segment] = []
        tail: List[Segment] = []
        if cand.mode == "open":
            body = reverse_path(self.segments) if cand.value else list(self.segments)
        elif cand.mode == "closed":
            body = rotate_closed_path(self.segments, cand.value)
        elif cand.mode == "lead_in":
            li = self.lead_ins[int(cand.value)]
            body = rotate_closed_path(self.segments, locate(self.segments, li.end))
            lead = list(li.segments)
            if dist(li.end, body[0].start) > JOIN_TOL:
                lead.append(LineSeg(li.end, body[0].start))
            lo = _matching_lead_out(self.lead_outs, body[0].start)
            if lo is not None:
                tail = _joined(body[0].start, lo.segments)
        else:  # lead_out
            lo = self.lead_outs[int(cand.value)]
            body = rotate_closed_path(self.segments, locate(self.segments, lo.start))
            tail = _joined(body[0].start, lo.segments)
        body = [s for s in body if s.length > 1e-9] or body[:1]
        segs = lead + body + tail
        entry = body[0].start
        return CutItem(contour_id=self.contour_id, part_id=self.part_id, kind=self.kind,
                       entry=entry, segments=segs, lead_in_count=len(lead),
                       lifts=lift_indices(segs, lift_angle), lead_out_count=len(tail))


def _joined(at: Point, segs: Sequence[Segment]) -> List[Segment]:
    out = list(segs)
    if dist(at, out[0].start) > JOIN_TOL:
        out.insert(0, LineSeg(at, out[0].start))
    return out


def _matching_lead_out(lead_outs: Sequence[LeadIn], p: Point, tol: float = 0.05) -> Optional[LeadIn]:
    for lo in lead_outs:
        if dist(lo.start, p) <= tol:
            return lo
    return None


@dataclass
class _Group:
    """A contour or open chain before common edges are dropped."""

    contour_id: str
    part_id: str
    kind: str
    segments: List[Segment]
    closed: bool
    shared: List[int] = field(default_factory=list)
    lead_ins: List[LeadIn] = field(default_factory=list)
    lead_outs: List[LeadIn] = field(default_factory=list)
    preds: List[int] = field(default_factory=list)


def _polygon(segments: Sequence[Segment]):
    from shapely.geometry import Polygon

    from ..geometry import path_points
    pts = path_points(segments, 0.1)
    poly = Polygon(pts)
    return poly if poly.is_valid else poly.buffer(0)


def build_items(parts: Sequence[Part], open_chains: Sequence[OpenChain], *,
                entry_spacing: float, max_candidates: int, cut_open_chains: bool,
                common_edge_tol: float) -> Tuple[List[PlanItem], List[List[int]], List[Finding]]:
    """Plan items in drawing order, their predecessor lists and findings."""
    findings: List[Finding] = []
    active = [p for p in parts if not p.excluded]
    n_excl = len(parts) - len(active)
    if n_excl:
        findings.append(Finding("info", "excluded-parts",
                                f"{n_excl} excluded part(s) are not cut"))
    groups: List[_Group] = []
    outer_of: Dict[str, int] = {}
    holes_of: Dict[str, List[int]] = {}
    for p in active:
        leads = {}
        for li in p.lead_ins:
            leads.setdefault(li.contour_id, []).append(li)
        hole_idx = []
        for h in p.holes:
            groups.append(_Group(h.id, p.id, "hole", list(h.segments), True, list(h.shared),
                                 [x for x in leads.get(h.id, []) if x.role == "lead_in"],
                                 [x for x in leads.get(h.id, []) if x.role == "lead_out"]))
            hole_idx.append(len(groups) - 1)
        o = p.outer
        groups.append(_Group(o.id, p.id, "outer", list(o.segments), True, list(o.shared),
                             [x for x in leads.get(o.id, []) if x.role == "lead_in"],
                             [x for x in leads.get(o.id, []) if x.role == "lead_out"],
                             preds=list(hole_idx)))
        outer_of[p.id] = len(groups) - 1
        holes_of[p.id] = hole_idx
        known = {h.id for h in p.holes} | {o.id}
        for cid in leads:
            if cid not in known:
                findings.append(Finding("warning", "lead-in-unknown-contour",
                                        f"lead-in of part {p.id} refers to unknown contour {cid}; ignored",
                                        source=cid))
    # parts inside holes of other parts
    polys = {gi: _polygon(g.segments) for gi, g in enumerate(groups) if g.kind == "hole"}
    boxes = {gi: poly.bounds for gi, poly in polys.items()}
    from shapely.geometry import Point as SPoint
    for p in active:
        gi_outer = outer_of[p.id]
        material = _polygon(groups[gi_outer].segments)
        for h in holes_of[p.id]:
            material = material.difference(polys[h])
        rep = (material if not material.is_empty else
               _polygon(groups[gi_outer].segments)).representative_point()
        host = None
        for gi, poly in polys.items():
            x0, y0, x1, y1 = boxes[gi]
            if groups[gi].part_id == p.id or not (x0 <= rep.x <= x1 and y0 <= rep.y <= y1):
                continue
            if poly.contains(rep) and (host is None or poly.area < polys[host].area):
                host = gi
        if host is not None:
            groups[host].preds.append(gi_outer)
        elif p.parent_id is not None:
            if p.parent_id in outer_of:
                groups[outer_of[p.parent_id]].preds.append(gi_outer)
            else:
                findings.append(Finding("warning", "unknown-parent",
                                        f"part {p.id} lies in part {p.parent_id}, which is not cut",
                                        source=p.id))
    closed_groups = list(range(len(groups)))
    if cut_open_chains:
        tree = None
        for ch in open_chains:
            if not ch.segments:
                continue
            groups.append(_Group(ch.id, "", "open", list(ch.segments), False))
            gi = len(groups) - 1
            if tree is None:
                from shapely import STRtree
                outline = [_polygon(groups[g].segments).buffer(1e-6) for g in closed_groups]
                areas = [poly.area for poly in outline]
                tree = STRtree(outline)
            seg0 = ch.segments[0]
            mid = SPoint(seg0.point_at(seg0.length / 2.0))
            inside = [int(i) for i in tree.query(mid, predicate="within")]
            if inside:
                host = min(inside, key=lambda i: (areas[i], i))
                groups[closed_groups[host]].preds.append(gi)
    elif open_chains:
        findings.append(Finding("info", "open-chains-not-cut",
                                f"{len(open_chains)} open chain(s) are not cut (cut_open_chains off)"))

    # rank = a precedence-respecting drawing order: the earlier of two
    # contours sharing an edge keeps it
    g_succs: List[List[int]] = [[] for _ in groups]
    for gi, g in enumerate(groups):
        for q in g.preds:
            g_succs[q].append(gi)
    try:
        rank_order = repair(list(range(len(groups))), [g.preds for g in groups], g_succs)
    except ValueError:
        from ..errors import InputError
        raise InputError("parts contain each other in a cycle (check parent/hole nesting)")
    rank = [0] * len(groups)
    for r, gi in enumerate(rank_order):
        rank[gi] = r
    shared_src = [(groups[gi].contour_id, groups[gi].segments, groups[gi].shared) for gi in closed_groups]
    pairs = match_shared(shared_src, common_edge_tol)
    drops = edges_to_drop(pairs, [rank[gi] for gi in closed_groups])
    unmatched = sum(len(g.shared) for g in groups) - 2 * len(pairs)
    if unmatched > 0:
        findings.append(Finding("info", "shared-edge-unmatched",
                                f"{unmatched} segment(s) marked shared have no twin; cut normally"))
    owner_of: Dict[int, List[int]] = {}
    for (ci, _), (cj, _) in pairs:
        a, b = (ci, cj) if rank[ci] < rank[cj] else (cj, ci)
        owner_of.setdefault(b, []).append(a)

    items: List[PlanItem] = []
    items_of: List[List[int]] = []
    for gi, g in enumerate(groups):
        dropped = drops.get(gi, set())
        if g.closed and dropped:
            runs = open_runs(g.segments, dropped)
            if g.lead_ins or g.lead_outs:
                findings.append(Finding("warning", "lead-in-dropped",
                                        f"contour {g.contour_id} shares edges with another part; "
                                        "its lead-in is not used", source=g.contour_id))
            idx = []
            for r in runs:
                it = PlanItem(g.contour_id, g.part_id, g.kind, r, False, partial=True)
                it.cands = [Cand(r[0].start, r[-1].end, "open", 0), Cand(r[-1].end, r[0].start, "open", 1)]
                items.append(it)
                idx.append(len(items) - 1)
            items_of.append(idx)
            continue
        it = PlanItem(g.contour_id, g.part_id, g.kind, g.segments, g.closed, g.lead_ins, g.lead_outs)
        if not g.closed:
            it.cands = [Cand(g.segments[0].start, g.segments[-1].end, "open", 0),
                        Cand(g.segments[-1].end, g.segments[0].start, "open", 1)]
        elif g.lead_ins:
            for k, li in enumerate(g.lead_ins):
                s = locate(g.segments, li.end)
                join = rotate_closed_path(g.segments, s)[0].start
                lo = _matching_lead_out(g.lead_outs, join)
                it.cands.append(Cand(li.start, lo.end if lo else join, "lead_in", k))
        elif g.lead_outs:
            for k, lo in enumerate(g.lead_outs):
                s = locate(g.segments, lo.start)
                join = rotate_closed_path(g.segments, s)[0].start
                it.cands.append(Cand(join, lo.end, "lead_out", k))
        else:
            for s in entry_positions(g.segments, entry_spacing, max_candidates):
                p = rotate_closed_path(g.segments, s)[0].start if s > 0 else g.segments[0].start
                it.cands.append(Cand(p, p, "closed", s))
        items.append(it)
        items_of.append([len(items) - 1])
    preds: List[List[int]] = [[] for _ in items]
    for gi, g in enumerate(groups):
        before = [q for pg in g.preds for q in items_of[pg]]
        before += [q for og in owner_of.get(gi, []) for q in items_of[og]]
        for k in items_of[gi]:
            preds[k] = sorted(set(before))
    return items, preds, findings
