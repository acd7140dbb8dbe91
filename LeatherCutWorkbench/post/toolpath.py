"""CutPlan -> neutral moves: the one machine-independent job every writer reads.

A :class:`Move` is a rapid, a straight or circular cut, a knife/torch up or down,
a turn of the knife in the air, an I/O event, a dwell or a sync point.  Every
move carries the id of the plan segment it belongs to (``"<item>:<segment>"``,
both 1-based, the id the live link journals and resumes from; ``""`` for moves
between segments such as the header or the lift after an item).  Sync points
close every item (``sync_at_items``) and, with ``sync_every_segment``, every
segment too (after its last cut, carrying that segment's id).

Knife heading (tangential knives only): the heading of the path tangent in
degrees (0 = +X, counter-clockwise positive) plus the profile's
``heading_offset``, kept *continuous* (unwrapped): every change takes the short
way round (|turn| <= 180 degrees).  Writers convert it to axis units and, for a
wrapped LinuxCNC axis, to the sign-selects-direction form.

Lifts: the profile is authoritative for the machine, so the knife is lifted,
turned in the air and plunged again before every joint whose heading change
exceeds ``profile.lift_angle``; the planner's ``CutItem.lifts`` are honoured as
well (the union of both is used), so a planner run with a smaller angle can only
add lifts, never remove one the machine needs.  Torches and drag knives never
lift inside an item, except over a tab (profile ``tab_count`` / ``tab_spacing``,
:mod:`.tabs`): up, rapid across the tab, down and pierce again.

Controller kerf compensation (profile ``kerf_mode == "controller"``): a
``comp`` move (``name`` ``left`` / ``right``, the side the scrap lies on)
before the tool goes down on a closed contour, ``comp`` ``off`` after it.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from typing import List, Optional, Tuple

from ..core.geometry import ArcSeg, CurveSeg, LineSeg, Point, Segment, dist, turn_angle
from ..core.model import CutItem, CutPlan
from . import drag_knife
from .profiles import MachineProfile

#: Longest arc piece (degrees of sweep) a tangential knife gets in one move.
#: Keeps a wrapped rotary axis unambiguous (< 180) and rotary feed moderate.
MAX_TANGENTIAL_ARC_SWEEP = 90.0


@dataclass
class Move:
    """One neutral move.  Coordinates are plan coordinates in mm (the writer adds
    the profile origin); ``heading`` is the continuous knife angle in degrees at
    the end of the move (None for tools without a heading axis)."""

    kind: str                      # rapid | line | arc | up | down | turn | io | dwell | sync
    seg: str = ""                  # "<item>:<segment>" or "" between segments
    x: float = 0.0
    y: float = 0.0
    heading: Optional[float] = None
    center: Optional[Point] = None  # arc centre (mm)
    ccw: bool = True                # arc direction
    feed: float = 0.0               # mm/min for rapid/line/arc
    name: str = ""                  # io: vacuum_on, tool_off, ...; comment text
    seconds: float = 0.0            # dwell
    item: int = 0                   # 1-based item index (0 = none)
    start: Point = (0.0, 0.0)       # where the move begins (mm)


@dataclass
class Toolpath:
    """Neutral job: moves in order plus the segment ids in cutting order."""

    moves: List[Move] = field(default_factory=list)
    segment_ids: List[str] = field(default_factory=list)
    item_labels: List[str] = field(default_factory=list)


def seg_id(item_index: int, seg_index: int) -> str:
    """Segment id used by writers, the journal and ``--resume-from`` (1-based)."""
    return f"{item_index}:{seg_index}"


def shortest_heading(current: Optional[float], target: float) -> float:
    """``target`` (degrees, any range) re-expressed near ``current`` so the turn
    takes the short way: the result differs from ``current`` by at most 180."""
    if current is None:
        return (target + 180.0) % 360.0 - 180.0
    d = (target - current + 180.0) % 360.0 - 180.0
    return current + d


def _pieces(seg: Segment, profile: MachineProfile) -> List[Segment]:
    """Split a segment into the pieces one machine move each can follow:
    polylines into lines, arcs into lines (profile ``arcs == "split"``, within
    ``chord_tol``) or, for a tangential knife, arcs of at most 90 degrees."""
    if isinstance(seg, LineSeg):
        return [seg]
    if isinstance(seg, CurveSeg):
        return [LineSeg(a, b) for a, b in zip(seg.pts, seg.pts[1:]) if dist(a, b) > 1e-9]
    if isinstance(seg, ArcSeg):
        if profile.arcs == "split" or profile.dialect == "hpgl":
            pts = seg.points(profile.chord_tol)
            return [LineSeg(a, b) for a, b in zip(pts, pts[1:])]
        limit = MAX_TANGENTIAL_ARC_SWEEP if profile.tangential else 180.0
        n = max(1, int(math.ceil(abs(seg.sweep) / limit - 1e-9)))
        step = seg.sweep / n
        return [ArcSeg(seg.center, seg.radius, seg.start_angle + k * step, step)
                for k in range(n)]
    raise TypeError(f"unknown segment type {type(seg).__name__}")


def _overcut(item: CutItem, length: float) -> List[Segment]:
    """The first ``length`` mm of a closed contour (after its lead-in), cut again
    past the entry so the start and end of the cut overlap."""
    contour = item.segments[item.lead_in_count:len(item.segments) - item.lead_out_count]
    out: List[Segment] = []
    left = length
    for seg in contour:
        if left <= 1e-9:
            break
        if seg.length <= left:
            out.append(seg)
            left -= seg.length
        else:
            out.append(seg.split_at(left)[0])
            left = 0.0
    return out


def _is_closed(item: CutItem) -> bool:
    contour = item.segments[item.lead_in_count:len(item.segments) - item.lead_out_count]
    return item.kind in ("outer", "hole") and bool(contour) and \
        dist(contour[0].start, contour[-1].end) < 1e-6


def build_toolpath(plan: CutPlan, profile: MachineProfile, overcut: Optional[float] = None
                   ) -> Toolpath:
    """Turn ``plan`` into neutral moves for ``profile``.

    ``overcut`` (mm, default the profile's) re-cuts the start of every closed
    contour.  Invariants: the knife is down only during line/arc moves; every
    rapid starts with the knife up; headings change by at most 180 degrees per
    move; with a tangential knife no joint inside a cut turns by more than the
    lift angle without an up/turn/down."""
    from . import tabs
    from .cut_direction import scrap_on_left
    tp = Toolpath()
    mv = tp.moves
    tab_gaps = tabs.plan_tabs(plan, profile)
    controller = profile.kerf_mode == "controller" and profile.kerf > 0
    tangential = profile.tangential
    oc = profile.overcut if overcut is None else overcut
    here: Point = plan.home
    heading: Optional[float] = None
    blade: Optional[float] = drag_knife.START_DIRECTION   # drag-knife blade heading

    def add(kind: str, **kw) -> Move:
        m = Move(kind, start=here, **kw)
        mv.append(m)
        return m

    for name in ("vacuum_on", "press_on"):
        if getattr(profile, name):
            add("io", name=name)
    if profile.settle_dwell > 0 and (profile.vacuum_on or profile.press_on):
        add("dwell", seconds=profile.settle_dwell)

    for i, item in enumerate(plan.items, 1):
        tp.item_labels.append(f"{item.kind} {item.part_id}/{item.contour_id}")
        segs = list(item.segments)
        ids = [seg_id(i, j) for j in range(1, len(segs) + 1)]
        tp.segment_ids.extend(ids)
        lift_before = set(item.lifts)
        # controller compensation trims the contour's first piece where a lead
        # meets it at an angle: the overcut (at least one kerf) cuts that
        # stretch too.  A lead-out starts at the entry: no overcut then.
        oc_item = 0.0 if item.lead_out_count else max(oc, profile.kerf) if controller else oc
        extra: List[Segment] = _overcut(item, oc_item) if oc_item > 0 and _is_closed(item) else []
        work: List[Tuple[Segment, str, bool, bool]] = [
            (s, ids[j], j in lift_before, True) for j, s in enumerate(segs)]
        work += [(s, ids[-1], False, True) for s in extra]
        if profile.blade_offset > 0:       # drag knife: the axis path that makes the tip cut `work`
            pieces, blade = drag_knife.compensate([w[0] for w in work], profile.blade_offset,
                                                  profile.swivel_angle, blade,
                                                  drag_knife.swivel_tolerance(profile))
            work = [(s, work[k][1], False, True) for s, k in pieces]
        work = tabs.split(work, tab_gaps.get(i - 1, ()))
        if not work:
            continue
        first_pieces = _pieces(work[0][0], profile)
        if not first_pieces:
            continue
        h0 = first_pieces[0].start_heading() + profile.heading_offset if tangential else None
        # travel with the knife up, pre-rotated to the first heading; the axis
        # unwinds in the air once it is more than a turn away from zero
        if tangential:
            heading = shortest_heading(heading, h0)
            if abs(heading) > 360.0:
                heading = shortest_heading(None, h0)
        start = first_pieces[0].start
        add("rapid", seg=ids[0], x=start[0], y=start[1], heading=heading,
            feed=profile.rapid_feed, item=i)
        here = start
        comp = controller and _is_closed(item)
        comp_side = ""
        if comp:
            body = item.segments[item.lead_in_count:len(item.segments) - item.lead_out_count]
            comp_side = "left" if scrap_on_left(body, item.kind) else "right"
        if profile.tool_on:
            add("io", seg=ids[0], name="tool_on", item=i)
        add("down", seg=ids[0], item=i)
        if profile.pierce_delay > 0:
            add("dwell", seg=ids[0], seconds=profile.pierce_delay, item=i)
        first = True
        in_tab = False
        for w, (seg, sid, planned_lift, cutting) in enumerate(work):
            if not cutting:               # a tab: across it with the tool up
                if not in_tab:
                    add("up", seg=sid, item=i)
                in_tab = True
                here = seg.end
                add("rapid", seg=sid, x=here[0], y=here[1], heading=heading,
                    feed=profile.rapid_feed, item=i)
                continue
            if in_tab:                    # after a tab: down and pierce again
                in_tab = False
                add("down", seg=sid, item=i)
                if profile.pierce_delay > 0:
                    add("dwell", seg=sid, seconds=profile.pierce_delay, item=i)
            for k, piece in enumerate(_pieces(seg, profile)):
                if piece.length <= 1e-9:
                    continue
                if comp_side and w < item.lead_in_count and isinstance(piece, LineSeg) \
                        and piece.length > 0.55 * profile.kerf:
                    # LinuxCNC enters compensation on a straight move longer
                    # than the tool radius: the first such move of the lead-in
                    add("comp", seg=sid, name=comp_side, item=i)
                    comp_side = ""
                if tangential:
                    h_start = piece.start_heading() + profile.heading_offset
                    turn = turn_angle(heading, h_start) if heading is not None else 0.0
                    if not first and (turn > profile.lift_angle + 1e-9
                                      or (planned_lift and k == 0)):
                        add("up", seg=sid, item=i)
                        heading = shortest_heading(heading, h_start)
                        add("turn", seg=sid, x=here[0], y=here[1], heading=heading, item=i)
                        add("down", seg=sid, item=i)
                    else:
                        heading = shortest_heading(heading, h_start)
                first = False
                end = piece.end
                if isinstance(piece, ArcSeg):
                    if tangential:
                        heading = heading + piece.sweep
                    add("arc", seg=sid, x=end[0], y=end[1], heading=heading,
                        center=piece.center, ccw=piece.sweep > 0, feed=profile.cut_feed, item=i)
                else:
                    add("line", seg=sid, x=end[0], y=end[1], heading=heading,
                        feed=profile.cut_feed, item=i)
                here = end
            if profile.sync_every_segment and (w + 1 == len(work) or work[w + 1][1] != sid):
                # the segment's last line: its ok means the segment was executed
                add("sync", seg=sid, item=i)
        if comp_side:
            from ..core.errors import InputError
            raise InputError(f"{item.kind} contour {item.contour_id} has no straight lead-in move "
                             f"longer than half the kerf to enter cutter compensation on (profile "
                             f"field kerf_mode 'controller'): give it a lead-in or use kerf_mode "
                             f"'path'", source=profile.source or profile.name)
        if comp:
            add("comp", name="off", item=i)
        add("up", item=i)
        if profile.cooling_delay > 0:
            add("dwell", seconds=profile.cooling_delay, item=i)
        if profile.tool_off:
            add("io", name="tool_off", item=i)
        if profile.sync_at_items:
            add("sync", item=i)

    add("rapid", x=plan.home[0], y=plan.home[1], heading=heading, feed=profile.rapid_feed)
    here = plan.home
    for name in ("press_off", "vacuum_off"):
        if getattr(profile, name):
            add("io", name=name)
    return tp
