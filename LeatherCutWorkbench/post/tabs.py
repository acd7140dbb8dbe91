"""Tabs (micro-joints): short pieces of an outer contour left uncut so the part
stays in the sheet, from the profile's ``tab_count`` / ``tab_spacing`` and
``tab_width`` (mm).

Tabs go on closed outer contours only (a hole's slug may fall out), spread
evenly along the contour body between its lead-in and lead-out, never within
one tab width of the entry, and never on a common edge: a tab whose stretch
comes within :data:`COMMON_TOL` of another cut item's path slides along the
contour until it is clear, or is left out.  Positions are arc lengths (mm)
along the item's segments in cutting order.
"""

from __future__ import annotations

from typing import Dict, List, Sequence, Tuple

from ..core.geometry import Segment, dist, path_points
from ..core.model import CutItem, CutPlan
from .profiles import MachineProfile

#: A tab this close (mm) to another item's path would sit on a common edge.
COMMON_TOL = 0.1


def wants_tabs(profile: MachineProfile) -> bool:
    return profile.tab_count > 0 or profile.tab_spacing > 0


def _body_range(item: CutItem) -> Tuple[float, float]:
    lengths = [s.length for s in item.segments]
    start = sum(lengths[:item.lead_in_count])
    end = sum(lengths) - sum(lengths[len(lengths) - item.lead_out_count:]) \
        if item.lead_out_count else sum(lengths)
    return start, end


def _closed_outer(item: CutItem) -> bool:
    body = item.segments[item.lead_in_count:len(item.segments) - item.lead_out_count]
    return item.kind == "outer" and bool(body) and dist(body[0].start, body[-1].end) < 1e-6


def plan_tabs(plan: CutPlan, profile: MachineProfile) -> Dict[int, List[Tuple[float, float]]]:
    """Item index (0-based) -> sorted (start, end) arc-length intervals (mm) to
    leave uncut."""
    if not wants_tabs(profile):
        return {}
    from shapely import STRtree
    from shapely.geometry import LineString, Point as SPoint

    lines = [LineString(path_points(it.segments, 0.05)) if len(it.segments) else None
             for it in plan.items]
    valid = [k for k, g in enumerate(lines) if g is not None and g.length > 0]
    tree = STRtree([lines[k] for k in valid])
    w = profile.tab_width
    out: Dict[int, List[Tuple[float, float]]] = {}
    for i, item in enumerate(plan.items):
        if not _closed_outer(item):
            continue
        b0, b1 = _body_range(item)
        length = b1 - b0
        n = int(length // profile.tab_spacing) if profile.tab_spacing > 0 else profile.tab_count
        lo, hi = b0 + w, b1 - 2.0 * w          # keep clear of the entry
        if n <= 0 or hi - lo < w:
            continue
        step = length / n

        def clear(s: float) -> bool:
            for a in (s, s + w / 2.0, s + w):
                p = SPoint(point_along(item.segments, a))
                for k in tree.query(p.buffer(COMMON_TOL)):
                    if valid[int(k)] != i and lines[valid[int(k)]].distance(p) < COMMON_TOL:
                        return False
            return True

        tabs: List[Tuple[float, float]] = []
        for k in range(n):
            centre = b0 + step * (k + 0.5) - w / 2.0
            for shift in [j * w * sgn for j in range(int(step / (2 * w)) + 1) for sgn in (1, -1)]:
                s = min(max(centre + shift, lo), hi)
                if clear(s) and all(s > e + w or s + w < a - w for a, e in tabs):
                    tabs.append((s, s + w))
                    break
        if tabs:
            out[i] = sorted(tabs)
    return out


def point_along(segments: Sequence[Segment], s: float):
    """The point ``s`` mm along a connected path (clamped to its end)."""
    acc = 0.0
    for seg in segments:
        if acc + seg.length >= s:
            return seg.point_at(s - acc)
        acc += seg.length
    return segments[-1].end


def split(work: List[tuple], intervals: Sequence[Tuple[float, float]]) -> List[tuple]:
    """``work`` entries ``(segment, seg_id, lift, cut)`` split at the tab
    intervals (arc lengths from the start of ``work``); pieces inside a tab get
    ``cut`` False."""
    if not intervals:
        return work
    cuts = sorted({x for iv in intervals for x in iv})
    out: List[tuple] = []
    acc = 0.0
    for seg, sid, lift, cut in work:
        rest, start = seg, acc
        for x in cuts:
            if start + 1e-9 < x < start + rest.length - 1e-9:
                head, rest = rest.split_at(x - start)
                out.append((head, sid, lift, cut and not _inside(start, x, intervals)))
                lift, start = False, x
        out.append((rest, sid, lift, cut and not _inside(start, start + rest.length, intervals)))
        acc += seg.length
    return out


def _inside(a: float, b: float, intervals: Sequence[Tuple[float, float]]) -> bool:
    m = (a + b) / 2.0
    return any(s <= m <= e for s, e in intervals)
