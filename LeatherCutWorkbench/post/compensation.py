"""Parts as the tool must follow them: cut direction, kerf offset, lead-ins.

Runs between arranging the parts (nesting or not) and planning, driven by the
machine profile (docs/MACHINES.md, "Kerf, cut direction, lead-ins and tabs"):

1. every closed contour is turned to the profile's cut direction
   (:mod:`.cut_direction`);
2. with ``kerf > 0`` and ``kerf_mode == "path"`` it is offset by ``kerf / 2``
   to the scrap side (:mod:`.kerf`); a contour that vanishes, splits or has a
   feature narrower than the kerf raises InputError naming the contour and the
   profile field, so nothing is written;
3. where the drawing has no lead-in for a contour and the profile asks for one
   (a torch always), lead-ins (and lead-outs) are generated at the planner's
   entry candidates (:mod:`.leads`); only those whose band clears every part
   and defect are offered, so the planner chooses among collision-free entries
   only.  A contour without any is reported (finding ``no-lead-in``) and cut
   without a lead-in.

The planner then sees the compensated contours; the drawn parts stay what the
preview fills and the kerf check compares against.
"""

from __future__ import annotations

import math
from dataclasses import replace
from typing import Any, List, Optional, Sequence, Tuple

from ..core.errors import InputError
from ..core.geometry import (ArcSeg, LineSeg, Segment, path_points, reverse_path,
                             rotate_closed_path)
from ..core.model import Contour, Finding, LeadIn, Part
from . import leads
from .cut_direction import oriented, scrap_on_left
from .kerf import OffsetError, offset_closed
from .profiles import MachineProfile

#: Lead lengths tried, as fractions of the profile length, before giving up.
LEAD_SCALES = (1.0, 0.5, 0.25)
#: At most this many generated lead-ins per contour are offered to the planner.
MAX_LEAD_CANDIDATES = 24


def lead_shapes(profile: MachineProfile) -> Tuple[str, str]:
    """(lead-in shape, lead-out shape): ``none``, ``line`` or ``arc``, with the
    tool defaults filled in (torch: arc lead-in, lead-out like the lead-in).
    Controller compensation always gets arcs: LinuxCNC trims an inside corner
    against one neighbouring move only, so a straight lead meeting the contour
    at an angle is refused wherever the contour's next piece is short."""
    lin = profile.lead_in or ("arc" if profile.tool == "torch" else "none")
    lout = profile.lead_out or (lin if profile.tool == "torch" else "none")
    if profile.kerf_mode == "controller" and profile.kerf > 0:
        lin, lout = ("arc" if lin != "none" else lin), ("arc" if lout != "none" else lout)
    return lin, lout


def active(profile: MachineProfile) -> bool:
    """Whether the profile changes the contours at all (else the parts are
    planned exactly as drawn and today's output is unchanged)."""
    from .cut_direction import wanted_ccw
    return (profile.kerf > 0 or lead_shapes(profile) != ("none", "none")
            or wanted_ccw("outer", profile) is not None
            or wanted_ccw("hole", profile) is not None)


def reserve(profile: MachineProfile) -> float:
    """Room (mm) the tool needs beyond the drawn outline of a part: the kerf
    (the band the cut removes) plus how far a generated lead reaches out."""
    lin, lout = lead_shapes(profile)
    reach = max(leads.normal_extent(lin, profile.lead_in_length, profile.lead_in_angle),
                leads.normal_extent(lout, profile.lead_out_length, profile.lead_out_angle))
    return profile.kerf + reach


def reserve_in_nesting(nest_options: Any, profile: MachineProfile) -> None:
    """Widen the nesting spacing and margin by :func:`reserve`: the spacing the
    user gives is then the web of material left between two cut bands."""
    extra = reserve(profile)
    if nest_options is None or extra <= 0:
        return
    nest_options.spacing += extra
    nest_options.margin += extra


def _polygon(segments: Sequence[Segment]):
    from shapely.geometry import Polygon
    poly = Polygon(path_points(segments, 0.01))
    return poly if poly.is_valid else poly.buffer(0)


def material(part: Part):
    """The part's material as a shapely polygon (outer minus holes), drawn."""
    poly = _polygon(part.outer.segments)
    for h in part.holes:
        poly = poly.difference(_polygon(h.segments))
    return poly


def _offset(c: Contour, kind: str, part: Part, segs: List[Segment],
            profile: MachineProfile) -> List[Segment]:
    d = profile.kerf / 2.0
    left = scrap_on_left(segs, kind)
    try:
        return offset_closed(segs, d if left else -d, profile.kerf_corners)
    except OffsetError as exc:
        where = f" near ({exc.where[0]:.2f}, {exc.where[1]:.2f})" if exc.where else ""
        raise InputError(f"kerf {profile.kerf:g} mm (profile field kerf) is larger than a "
                         f"feature of {kind} contour {c.id} of part {part.id}{where}: {exc}",
                         source=profile.source or profile.name)


def _shifted(li: LeadIn, contour: Sequence[Segment]) -> LeadIn:
    """A drawn lead moved (its shape kept) so the end that meets the drawn
    contour meets the offset contour at the nearest point instead."""
    from ..core.geometry import Transform2D
    from ..core.pathplan.candidates import locate

    at = li.segments[-1].end if li.role == "lead_in" else li.segments[0].start
    s = locate(contour, at)
    p = rotate_closed_path(contour, s)[0].start if s > 0 else contour[0].start
    xf = Transform2D(dx=p[0] - at[0], dy=p[1] - at[1])
    return replace(li, segments=[seg.transformed(xf) for seg in li.segments])


def _variants(profile: MachineProfile) -> List[Tuple[str, str, float, float]]:
    """(lead-in shape, lead-out shape, length scale, line angle) to try in turn.
    With controller compensation a square-on line lead-in without lead-out is
    the last resort (small holes, where no arc wider than the kerf fits)."""
    lin, lout = lead_shapes(profile)
    out = [(lin, lout, k, profile.lead_in_angle) for k in LEAD_SCALES]
    if profile.kerf_mode == "controller" and profile.kerf > 0 and lin != "none":
        out += [("line", "none", k, 90.0) for k in LEAD_SCALES]
    return out


def _against_drawn_lead(segs: Sequence[Segment], drawn: Sequence[LeadIn]) -> bool:
    """Whether the first drawn lead-in arrives against the direction of ``segs``
    (its last heading and the contour's heading at the join differ by more than
    90 degrees)."""
    from ..core.geometry import turn_angle
    from ..core.pathplan.candidates import locate

    lead = next((li for li in drawn if li.role == "lead_in"), None)
    if lead is None:
        return False
    s = locate(segs, lead.segments[-1].end)
    path = rotate_closed_path(segs, s) if s > 0 else list(segs)
    return turn_angle(lead.segments[-1].end_heading(), path[0].start_heading()) > 90.0


def _entry_line(first: Segment, kerf: float) -> LineSeg:
    """A straight move of one kerf ending tangentially where ``first`` starts:
    LinuxCNC switches compensation on with a straight move longer than the
    tool radius."""
    h = math.radians(first.start_heading())
    return LineSeg((first.start[0] - kerf * math.cos(h), first.start[1] - kerf * math.sin(h)),
                   first.start)


def _with_entry_line(li: LeadIn, profile: MachineProfile) -> LeadIn:
    """A drawn lead-in with :func:`_entry_line` in front unless it starts
    with a long enough straight move already."""
    first = li.segments[0]
    if li.role != "lead_in" or (isinstance(first, LineSeg) and first.length > profile.kerf):
        return li
    return replace(li, segments=[_entry_line(first, profile.kerf)] + list(li.segments))


def _generated_leads(c: Contour, kind: str, segs: List[Segment], profile: MachineProfile,
                     obstacles: "leads.Obstacles", entry_spacing: float
                     ) -> List[LeadIn]:
    from ..core.geometry import Transform2D
    from ..core.pathplan.candidates import entry_positions

    half = profile.kerf / 2.0
    # controller compensation: the lead is written on the drawn contour and the
    # controller moves it half a kerf to the scrap side; it is checked there
    controller = profile.kerf_mode == "controller" and profile.kerf > 0
    left = scrap_on_left(segs, kind)
    positions = entry_positions(segs, entry_spacing, MAX_LEAD_CANDIDATES)
    for lin, lout, scale, angle in _variants(profile):
        found: List[LeadIn] = []
        for s in positions:
            path = rotate_closed_path(segs, s) if s > 0 else list(segs)
            p = path[0].start
            h_in, h_out = path[0].start_heading(), path[-1].end_heading()
            li = leads.lead_in(p, h_in, left, lin, profile.lead_in_length * scale,
                               angle) if lin != "none" else []
            lo = leads.lead_out(p, h_out, left, lout, profile.lead_out_length * scale,
                                profile.lead_out_angle) if lout != "none" else []
            if controller:
                if lin == "arc":
                    li.insert(0, _entry_line(li[0], profile.kerf))
                elif min(path[0].length, path[-1].length) <= profile.kerf:
                    continue              # LinuxCNC cannot trim the corner against a short piece
                if any(isinstance(g, ArcSeg) and g.radius <= profile.kerf for g in li + lo):
                    continue              # LinuxCNC needs arcs wider than the tool radius
                _, n = leads.frame(h_in, left)
                xf = Transform2D(dx=half * n[0], dy=half * n[1])
                check = [seg.transformed(xf) for seg in li + lo]
            else:
                check = li + lo
            if not leads.is_clear(check, half, obstacles):
                continue
            k = len(found) // 2
            if li:
                found.append(LeadIn(f"{c.id}#lead-in{k + 1}", c.id, li, "lead_in"))
            if lo:
                found.append(LeadIn(f"{c.id}#lead-out{k + 1}", c.id, lo, "lead_out"))
        if found:
            return found
    return []


def _contour(c: Contour, kind: str, part: Part, drawn: List[LeadIn], profile: MachineProfile,
             obstacles: Optional["leads.Obstacles"], entry_spacing: float,
             findings: List[Finding]) -> Tuple[Contour, List[LeadIn], bool]:
    """One contour as the tool follows it, its leads (drawn, moved onto the
    offset contour, or generated) and whether it has a lead-in at all."""
    controller = profile.kerf_mode == "controller"
    segs = oriented(c.segments, kind, profile)
    if _against_drawn_lead(segs, drawn):
        # the drawn lead-in wins: it was drawn for the other direction
        segs = reverse_path(segs)
        findings.append(Finding("info", "direction-from-lead-in",
                                f"contour {c.id} is cut the way its drawn lead-in enters it",
                                source=c.id))
    shared = list(c.shared)
    if list(segs) != list(c.segments):
        shared = sorted(len(segs) - 1 - i for i in shared)
    if profile.kerf > 0:
        comp = _offset(c, kind, part, segs, profile)
        if not controller:
            segs = comp
            if shared:
                findings.append(Finding(
                    "warning", "kerf-common-edge",
                    f"contour {c.id} shares edges with another part; with a kerf of "
                    f"{profile.kerf:g} mm each part is cut on its own", source=c.id))
            shared = []
    leads_of: List[LeadIn] = []
    if drawn:
        if profile.kerf > 0 and not controller:
            leads_of = [_shifted(li, segs) for li in drawn]
        elif controller and profile.kerf > 0:
            leads_of = [_with_entry_line(li, profile) for li in drawn]
        else:
            leads_of = list(drawn)
    elif obstacles is not None:
        leads_of = _generated_leads(c, kind, segs, profile, obstacles, entry_spacing)
    has_lead = any(li.role == "lead_in" for li in leads_of) or obstacles is None
    return replace(c, segments=list(segs), shared=shared), leads_of, has_lead


def compensate(parts: Sequence[Part], profile: MachineProfile, defects: Sequence = (),
               entry_spacing: float = 20.0) -> Tuple[List[Part], List[Finding]]:
    """The parts as the tool follows them (see module docstring) and findings.

    ``defects``: polygons (lists of points, mm) of hide defects leads must
    avoid.  A drawn lead whose band would cut into a part or a defect (e.g.
    after nesting moved its neighbours close) is dropped with a warning and
    replaced by a generated one.  Raises InputError when the kerf is larger
    than a feature."""
    from shapely.geometry import Polygon

    findings: List[Finding] = []
    active_parts = [p for p in parts if not p.excluded]
    lin, lout = lead_shapes(profile)
    want_leads = lin != "none" or lout != "none"
    mats = [material(p) for p in active_parts] if want_leads else []
    obstacles = leads.Obstacles(mats + [Polygon(d) for d in defects if len(d) >= 3]) \
        if want_leads else None
    shift = profile.kerf / 2.0 if profile.kerf_mode == "controller" else 0.0
    out: List[Part] = []
    no_lead: List[str] = []
    for part in parts:
        if part.excluded:
            out.append(part)
            continue
        new_leads: List[LeadIn] = []
        contours = []
        for kind, c in [("hole", h) for h in part.holes] + [("outer", part.outer)]:
            drawn = [li for li in part.lead_ins if li.contour_id == c.id]
            res = _contour(c, kind, part, drawn, profile, obstacles, entry_spacing, findings)
            if drawn and obstacles is not None and not all(
                    leads.is_clear(_as_cut(li, res[0].segments, kind, shift), profile.kerf / 2.0,
                                   obstacles) for li in res[1]):
                findings.append(Finding(
                    "warning", "drawn-lead-in-collides",
                    f"the drawn lead of contour {c.id} would cut into a part or a defect; "
                    "a lead is generated instead", source=c.id))
                res = _contour(c, kind, part, [], profile, obstacles, entry_spacing, findings)
            contour, leads_of, has_lead = res
            if not has_lead:
                no_lead.append(c.id)
            contours.append(contour)
            new_leads.extend(leads_of)
        out.append(replace(part, holes=contours[:-1], outer=contours[-1], lead_ins=new_leads))
    for cid in no_lead:
        findings.append(Finding("warning", "no-lead-in",
                                f"no collision-free lead-in fits contour {cid} (profile fields "
                                "lead_in_length / lead_in_angle); it is entered on the contour",
                                source=cid))
    return out, findings


def _as_cut(li: LeadIn, contour: Sequence[Segment], kind: str, shift: float) -> List[Segment]:
    """A drawn lead as the tool centre follows it: as written, or (controller
    compensation) moved ``shift`` mm square to the contour at its join."""
    if not shift:
        return list(li.segments)
    from ..core.geometry import Transform2D
    from ..core.pathplan.candidates import locate

    at = li.segments[-1].end if li.role == "lead_in" else li.segments[0].start
    s = locate(contour, at)
    path = rotate_closed_path(contour, s) if s > 0 else list(contour)
    _, n = leads.frame(path[0].start_heading(), scrap_on_left(contour, kind))
    xf = Transform2D(dx=shift * n[0], dy=shift * n[1])
    return [seg.transformed(xf) for seg in li.segments]


def job_hook(profile: MachineProfile, entry_spacing: float = 20.0):
    """The ``JobOptions.prepare`` callable for ``profile`` (None when the
    profile does not change the contours): parts, layout -> parts, findings."""
    if not active(profile):
        return None

    def prepare(parts: List[Part], layout: Optional[Any]) -> Tuple[List[Part], List[Finding]]:
        defects = [d for c in (layout.containers if layout is not None else []) for d in c.defects]
        return compensate(parts, profile, defects, entry_spacing)
    return prepare


def apply_to_job(options: Any, profile: MachineProfile) -> None:
    """Make a :class:`~..core.job.JobOptions` honour the profile: nesting
    reserves room for kerf and leads, and the parts are compensated before
    planning.  Used by the CLI and the workbench alike."""
    if not active(profile):
        return
    reserve_in_nesting(options.nest, profile)
    spacing = options.plan.entry_spacing if options.plan is not None else 20.0
    options.prepare = job_hook(profile, spacing)


def summary(plan: Any, profile: MachineProfile) -> dict:
    """What the tool does beyond the drawing, for ``report.json``: kerf and its
    mode, cut directions, lead counts and tabs (mm, counts)."""
    from .cut_direction import wanted_ccw
    from .tabs import plan_tabs

    def direction(kind: str) -> str:
        want = wanted_ccw(kind, profile)
        return "drawn" if want is None else ("ccw" if want else "cw")

    lin, lout = lead_shapes(profile)
    closed = [it for it in plan.items if it.kind in ("outer", "hole")]
    return {
        "kerf_mm": profile.kerf, "kerf_mode": profile.kerf_mode,
        "kerf_corners": profile.kerf_corners,
        "outer_direction": direction("outer"), "hole_direction": direction("hole"),
        "lead_in": lin, "lead_out": lout,
        "items_with_lead_in": sum(1 for it in closed if it.lead_in_count),
        "items_with_lead_out": sum(1 for it in closed if it.lead_out_count),
        "closed_items_without_lead_in": [it.contour_id for it in closed if not it.lead_in_count],
        "tabs": sum(len(v) for v in plan_tabs(plan, profile).values()),
    }
